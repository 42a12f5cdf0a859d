// interruption.h: what SIGINT, SIGTERM and SIGHUP do to lucent. The command-line tool installs handlers that, when
// a signal ends the process, first remove the files registered here (temporaries being written, lock files held),
// so an interrupted lucent leaves neither half-written files nor junk beside its outputs; the process then ends as
// the signal's default action would (the shell sees "terminated by SIGINT"). The handlers only unlink registered
// paths and re-raise: everything else is done by normal control flow.
//
// A long computation that can stop cleanly defers the signal instead (DeferredInterruption): the first signal is
// recorded, the work polls received() and stops at its next safe point (a reference saves the passes it completed);
// a second signal ends the process at once.
#pragma once
#include <string>

namespace lucent {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP. Without them (an application embedding the library) the
// registrations below are kept and unused, and a signal does what the application says.
void install_interruption_handlers();

// While alive, `path` is removed if a signal ends the process. At most 64 paths are registered at once (further ones
// are not: they would be left behind, as without the handlers).
class RemoveOnSignal {
 public:
  explicit RemoveOnSignal(const std::string& path);
  ~RemoveOnSignal();
  RemoveOnSignal(const RemoveOnSignal&) = delete;
  RemoveOnSignal& operator=(const RemoveOnSignal&) = delete;

 private:
  int slot_ = -1;
};

// While one is alive, the first SIGINT, SIGTERM or SIGHUP is recorded instead of ending the process. When the last
// one ends with a signal recorded and not taken, the process ends then (registered files removed): a short critical
// section (renaming a set of files into place) is never cut in the middle.
class DeferredInterruption {
 public:
  DeferredInterruption();
  ~DeferredInterruption();
  DeferredInterruption(const DeferredInterruption&) = delete;
  DeferredInterruption& operator=(const DeferredInterruption&) = delete;

  // The signal recorded (SIGINT, ...), or 0.
  int received() const;
  // The signal recorded, now the caller's to report (the process is no longer ended for it); 0 when none was.
  int take();
};

}  // namespace lucent
