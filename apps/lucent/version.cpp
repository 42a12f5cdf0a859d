// version.cpp: `lucent --version`; LUCENT_VERSION and LUCENT_GIT_DESCRIBE come from CMake (CMakeLists.txt).
#include <string>

#include "commands.h"

#ifndef LUCENT_VERSION
#define LUCENT_VERSION "unknown"
#endif
#ifndef LUCENT_GIT_DESCRIBE
#define LUCENT_GIT_DESCRIBE ""
#endif

namespace lucent::cli {

std::string version_text() {
  const std::string git = LUCENT_GIT_DESCRIBE;
  return std::string("lucent ") + LUCENT_VERSION + (git.empty() ? "" : " (git " + git + ")");
}

}  // namespace lucent::cli
