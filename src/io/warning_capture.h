// warning_capture.h: collects this thread's warnings instead of sending them to the handler (lucent/warning.h).
// A guarded reader's child process (scene/import_guard.h) captures its warnings and returns them with its result,
// so that the parent's handler (a Python warning, say) sees them; the child never calls the parent's handler.
#pragma once
#include <string>
#include <vector>

namespace lucent {

class WarningCapture {
 public:
  explicit WarningCapture(std::vector<std::string>* into);
  ~WarningCapture();
  WarningCapture(const WarningCapture&) = delete;
  WarningCapture& operator=(const WarningCapture&) = delete;

 private:
  std::vector<std::string>* previous_;
};

// `warnings` and `payload` as one byte string, and back: unpack_warnings warns each one (warn()) and returns the
// payload; a string too short to hold what its header says is returned as it is, with no warning.
std::string pack_warnings(const std::vector<std::string>& warnings, std::string payload);
std::string unpack_warnings(std::string packed);

}  // namespace lucent
