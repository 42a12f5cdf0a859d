// child_exit.h: the wait status of a child process the CPU tests started (a `lucent` sent a signal), waiting at most
// `limit_seconds`; a child still running then is killed (SIGKILL), so a broken build fails the test instead of
// hanging the run. Not a timing check: the limit is minutes.
#pragma once
#include <csignal>

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace lucent::test {

inline int wait_for_exit_or_kill(pid_t pid, int limit_seconds = 120) {
  int status = 0;
  for (int tries = 0; tries < 10 * limit_seconds && ::waitpid(pid, &status, WNOHANG) == 0; ++tries) ::usleep(100000);
  if (::waitpid(pid, &status, WNOHANG) == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  return status;
}

}  // namespace lucent::test
