// test_shader_sources.cpp: #include expansion over the embedded shader files, and driver logs mapped back to
// file names and lines.
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "gpu/shader_sources.h"
#include "lucent/error.h"

namespace lucent::gpu {
namespace {

bool ends_with(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

bool is_shader_stage(std::string_view path) {
  return ends_with(path, ".comp") || ends_with(path, ".vert") || ends_with(path, ".frag") || ends_with(path, ".geom");
}

std::size_t count(const std::string& text, std::string_view needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++n;
  return n;
}

bool contains(const std::vector<std::string>& files, std::string_view path) {
  for (const std::string& f : files)
    if (f == path) return true;
  return false;
}

TEST(ShaderSources, EmbedsShadersAndSharedHeaders) {
  ASSERT_GT(kEmbeddedFileCount, 0u);
  bool has_integrate = false, has_dipole = false;
  for (std::size_t i = 0; i < kEmbeddedFileCount; ++i) {
    std::string_view path = kEmbeddedFiles[i].path;
    has_integrate = has_integrate || path == "methods/radiosity_maps/shaders/integrate.comp";
    has_dipole = has_dipole || path == "bssrdf/directional_dipole.h";
    EXPECT_GT(kEmbeddedFiles[i].size, 0u) << path;
    EXPECT_EQ(kEmbeddedFiles[i].text[kEmbeddedFiles[i].size], '\0') << path;
  }
  EXPECT_TRUE(has_integrate);
  EXPECT_TRUE(has_dipole);
}

TEST(ShaderSources, EveryStageExpands) {
  int stages = 0;
  for (std::size_t i = 0; i < kEmbeddedFileCount; ++i) {
    const std::string path = kEmbeddedFiles[i].path;
    if (!is_shader_stage(path)) continue;
    ++stages;
    SCOPED_TRACE(path);
    try {
      ExpandedSource source = expand_shader(path);
      EXPECT_EQ(source.text.rfind("#version 450 core\n", 0), 0u);
      ASSERT_FALSE(source.files.empty());
      EXPECT_EQ(source.files[0], path);
      // No local #include survives expansion.
      EXPECT_EQ(source.text.find("#include \""), std::string::npos);
    } catch (const Error& error) {
      ADD_FAILURE() << error.what();
    }
  }
  EXPECT_GT(stages, 0);
}

TEST(ShaderSources, IntegrateIncludesDirectionalDipoleOnce) {
  ExpandedSource source = expand_shader("methods/radiosity_maps/shaders/integrate.comp");
  EXPECT_EQ(source.text.rfind("#version 450 core", 0), 0u);
  EXPECT_EQ(count(source.text, "LUCENT_INLINE float directional_dipole_Sd("), 1u);
  EXPECT_EQ(count(source.text, "LUCENT_INLINE vec3 refracted_direction("), 1u);
  ASSERT_FALSE(source.files.empty());
  EXPECT_EQ(source.files[0], "methods/radiosity_maps/shaders/integrate.comp");
  EXPECT_TRUE(contains(source.files, "bssrdf/directional_dipole.h"));
  EXPECT_TRUE(contains(source.files, "bssrdf/model.h"));
  EXPECT_TRUE(contains(source.files, "common/frame.glsl"));
  // Each file is listed once, however often it is included.
  for (std::size_t i = 0; i < source.files.size(); ++i)
    for (std::size_t j = i + 1; j < source.files.size(); ++j) EXPECT_NE(source.files[i], source.files[j]);
}

TEST(ShaderSources, DefinesFollowVersion) {
  ExpandedSource source = expand_shader("methods/radiosity_maps/shaders/integrate.comp", "#define LUCENT_TEST_DEFINE 1\n");
  EXPECT_EQ(source.text.rfind("#version 450 core\n#define LUCENT_TEST_DEFINE 1\n", 0), 0u);
}

TEST(ShaderSources, MissingFileThrowsNamingIt) {
  try {
    expand_shader("no/such.comp");
    ADD_FAILURE() << "expand_shader accepted a file that is not embedded";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()), "shader no/such.comp: included file 'no/such.comp' is not embedded");
  }
}

TEST(ShaderSources, AnnotateLogNamesFileAndLine) {
  ExpandedSource source = expand_shader("methods/radiosity_maps/shaders/integrate.comp");
  ASSERT_GE(source.files.size(), 2u);
  // Mesa style.
  EXPECT_EQ(source.annotate_log("0:12(5): error: x"), source.files[0] + ":12(5): error: x");
  EXPECT_EQ(source.annotate_log("0:12(5): error: x"), "methods/radiosity_maps/shaders/integrate.comp:12(5): error: x");
  // NVIDIA style, second source string.
  EXPECT_EQ(source.annotate_log("1(7) : error C0000: y"), source.files[1] + ":7 : error C0000: y");
  // Several references in a multi-line log.
  EXPECT_EQ(source.annotate_log("0:3(1): error: a\n1:4(2): warning: b\n"),
            source.files[0] + ":3(1): error: a\n" + source.files[1] + ":4(2): warning: b\n");
  // A source-string number with no file is left alone.
  EXPECT_EQ(source.annotate_log("99:3(1): error: z"), "99:3(1): error: z");
}

}  // namespace
}  // namespace lucent::gpu
