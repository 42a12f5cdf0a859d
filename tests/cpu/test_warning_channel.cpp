// The warning channel (lucent/warning.h): a handler receives every warning, including those of a guarded reader's
// child process, and the default handler's line is restored after a scoped one.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/warning_capture.h"
#include "lucent/warning.h"
#include "scene/import_guard.h"

namespace lucent {
namespace {

TEST(WarningChannel, HandlerReceivesMessagesAndScopeRestoresTheDefault) {
  std::vector<std::string> seen;
  {
    const ScopedWarningHandler handler([&](const std::string& m) { seen.push_back(m); });
    warn("a.json: first");
    warn("a.json: second");
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"a.json: first", "a.json: second"}));
  ::testing::internal::CaptureStderr();
  warn("b.json: after");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "lucent: warning: b.json: after\n");
  EXPECT_EQ(seen.size(), 2u);
}

TEST(WarningChannel, PackedWarningsRoundTripAndShortInputIsLeftAlone) {
  std::vector<std::string> seen;
  const ScopedWarningHandler handler([&](const std::string& m) { seen.push_back(m); });
  const std::string payload("bytes\0with nul", 14);
  EXPECT_EQ(unpack_warnings(pack_warnings({"one", "", "three"}, payload)), payload);
  EXPECT_EQ(seen, (std::vector<std::string>{"one", "", "three"}));
  seen.clear();
  EXPECT_EQ(unpack_warnings("abc"), "abc");  // shorter than a header: no warnings
  std::string truncated = pack_warnings({"a long warning"}, "");
  truncated.resize(truncated.size() - 3);
  EXPECT_EQ(unpack_warnings(truncated), truncated);
  EXPECT_TRUE(seen.empty());
}

TEST(WarningChannel, AGuardedReadersWarningsReachTheParentsHandler) {
  std::vector<std::string> seen;
  const ScopedWarningHandler handler([&](const std::string& m) { seen.push_back(m); });
  const std::string result = read_in_child(
      "mesh.obj", GuardedReader{},
      [] {
        warn("mesh.obj: texture coordinates dropped");
        return std::string("payload");
      },
      ImportLimits{});
  EXPECT_EQ(result, "payload");
  EXPECT_EQ(seen, (std::vector<std::string>{"mesh.obj: texture coordinates dropped"}));
}

}  // namespace
}  // namespace lucent
