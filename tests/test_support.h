// test_support.h: small helpers shared by the CPU tests: a temporary file named after the running test, a file's
// text, and the message of the lucent::Error a call throws.
#pragma once

// LUCENT_TEST_ASAN: defined when the tests are built with AddressSanitizer (GCC or clang), whose shadow memory
// makes address-space limits meaningless.
#if defined(__SANITIZE_ADDRESS__)
#define LUCENT_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LUCENT_TEST_ASAN 1
#endif
#endif

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include <gtest/gtest.h>

#include "lucent/error.h"

namespace lucent::test {

// A file in the test temp directory, named after the running test, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& extension) {
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    // The process id keeps two test runs on one machine (two checkouts, a sanitizer build) apart.
    path_ = std::filesystem::path(::testing::TempDir()) /
            (std::string("lucent_") + test->test_suite_name() + "_" + test->name() + "_" +
             std::to_string(::getpid()) + extension);
  }
  ~TempFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// A file's bytes ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The Error message a call throws, or "" when it does not throw.
template <class Call>
std::string error_message(Call call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

}  // namespace lucent::test
