// warning.h: lucent's warning channel, beside error.h's lucent::Error. Input that lucent accepts but that will not
// render what its author probably meant (a clamped albedo map, an open surface around a medium, a glTF field lucent
// does not read) gives one warning line naming the input. The command-line tool prints each as
// "lucent: warning: <message>" on stderr (the default handler); an embedding application (the Python module turns
// them into Python warnings) installs its own handler.
#pragma once
#include <functional>
#include <string>

namespace lucent {

// Called once per warning with the message (no "lucent: warning: " prefix, no newline). Called on the thread that
// warns; lucent serialises the calls.
using WarningHandler = std::function<void(const std::string& message)>;

// Sends `message` to the installed handler (by default: stderr, prefixed "lucent: warning: ").
void warn(const std::string& message);

// Installs `handler` (an empty one restores the default) and returns the previous one, so a caller can restore it.
WarningHandler set_warning_handler(WarningHandler handler);

// Installs a handler for as long as it lives, then restores the previous one.
class ScopedWarningHandler {
 public:
  explicit ScopedWarningHandler(WarningHandler handler) : previous_(set_warning_handler(std::move(handler))) {}
  ~ScopedWarningHandler() { set_warning_handler(std::move(previous_)); }
  ScopedWarningHandler(const ScopedWarningHandler&) = delete;
  ScopedWarningHandler& operator=(const ScopedWarningHandler&) = delete;

 private:
  WarningHandler previous_;
};

}  // namespace lucent
