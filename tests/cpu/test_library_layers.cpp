// test_library_layers.cpp: the three libraries stay apart: lucent_core (scenes, materials, method descriptions)
// and lucent_reference (the CPU references) include no GL header and nothing of the GL library, lucent_core
// nothing of Embree, oneTBB or the references. The sources of each library are read from CMakeLists.txt, so a file
// added to a library is checked too, and the method descriptions and precomputations (src/methods/*/*_info.cpp,
// *_precompute.cpp) with the core.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../test_support.h"
#include "../test_paths.h"

namespace {

namespace fs = std::filesystem;

using lucent::test::read_text;

// The src/... files listed in add_library(<name> ...) of the top-level CMakeLists.txt.
std::vector<std::string> library_sources(const std::string& name) {
  const std::string cmake = read_text(fs::path(LUCENT_SOURCE_DIR) / "CMakeLists.txt");
  const std::size_t start = cmake.find("add_library(" + name + " STATIC");
  EXPECT_NE(start, std::string::npos) << name;
  const std::size_t end = cmake.find(')', start);
  std::vector<std::string> files;
  std::istringstream lines(cmake.substr(start, end - start));
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, std::regex(R"(^\s*(src/\S+\.cpp))"))) files.push_back(m[1]);
  }
  return files;
}

void expect_no_include(const std::vector<std::string>& files, const std::regex& forbidden, const std::string& library) {
  for (const std::string& file : files) {
    std::istringstream lines(read_text(fs::path(LUCENT_SOURCE_DIR) / file));
    int number = 0;
    for (std::string line; std::getline(lines, line);) {
      ++number;
      if (line.rfind("#include", 0) == 0 && std::regex_search(line, forbidden))
        ADD_FAILURE() << file << ":" << number << ": " << library << " must not " << line;
    }
  }
}

TEST(LibraryLayers, CoreIncludesNoGlNoEmbreeNoReference) {
  std::vector<std::string> core = library_sources("lucent_core");
  ASSERT_GE(core.size(), 20u);
  for (const auto& entry : fs::directory_iterator(fs::path(LUCENT_SOURCE_DIR) / "src/methods"))
    if (entry.is_directory())
      for (const auto& file : fs::directory_iterator(entry.path()))
        if (file.path().filename().string().ends_with("_info.cpp") ||
            file.path().filename().string().ends_with("_precompute.cpp"))
          core.push_back(fs::relative(file.path(), LUCENT_SOURCE_DIR).string());
  const std::regex forbidden(
      R"(epoxy|GLFW|EGL|embree|tbb|"render/|"platform/|"methods/method\.h"|"reference/|"gpu/(?!shader_sources\.h))");
  expect_no_include(core, forbidden, "lucent_core");
}

// OpenVDB (and the oneTBB and Boost headers it brings) is compiled into one file, the library lucent_vdb; no other
// source or header of src/, include/ and apps/ includes it.
TEST(LibraryLayers, OpenVdbStaysInItsOwnFile) {
  const std::vector<std::string> vdb = library_sources("lucent_vdb");
  ASSERT_EQ(vdb, std::vector<std::string>{"src/media/medium_vdb.cpp"});
  std::vector<std::string> others;
  for (const char* folder : {"src", "include", "apps"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(LUCENT_SOURCE_DIR) / folder)) {
      const std::string file = fs::relative(entry.path(), LUCENT_SOURCE_DIR).string();
      if (entry.is_regular_file() && file != vdb[0] && (file.ends_with(".cpp") || file.ends_with(".h")))
        others.push_back(file);
    }
  ASSERT_GE(others.size(), 100u);
  expect_no_include(others, std::regex(R"(openvdb)"), "a file outside lucent_vdb");
}

// CGAL (header-only, about 22 s of compiler time a file) is included by the methods' *_cgal.cpp files alone, which
// build into lucent_cgal; no other source or header of src/, include/ and apps/ includes it.
TEST(LibraryLayers, CgalStaysInTheCgalFiles) {
  std::vector<std::string> others;
  std::size_t cgal_files = 0;
  for (const char* folder : {"src", "include", "apps"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(LUCENT_SOURCE_DIR) / folder)) {
      const std::string file = fs::relative(entry.path(), LUCENT_SOURCE_DIR).string();
      if (!entry.is_regular_file() || !(file.ends_with(".cpp") || file.ends_with(".h"))) continue;
      if (file.ends_with("_cgal.cpp")) ++cgal_files;
      else others.push_back(file);
    }
  EXPECT_GE(cgal_files, 1u);
  ASSERT_GE(others.size(), 100u);
  expect_no_include(others, std::regex(R"(CGAL/)"), "a file outside the *_cgal.cpp files");
}

TEST(LibraryLayers, ReferencesIncludeNoGl) {
  const std::vector<std::string> reference = library_sources("lucent_reference");
  ASSERT_GE(reference.size(), 5u);
  expect_no_include(reference, std::regex(R"(epoxy|GLFW|EGL|"render/|"platform/|"methods/method\.h"|"gpu/)"),
                    "lucent_reference");
}

}  // namespace
