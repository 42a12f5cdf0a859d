// test_bindings.cpp: the program's one table of binding points, texture units and image units
// (src/shared/bindings.h): no two ranges of a kind overlap, everything fits GL's guaranteed limits, and every
// binding #define or constant anywhere in the sources lies inside the range of the code that owns it, with no two
// slots of one owner on the same index. Also: no pass binds a literal slot number.
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "shared/bindings.h"
#include "../test_support.h"
#include "../test_paths.h"

namespace {

namespace fs = std::filesystem;
using lucent::shader::SlotKind;
using lucent::shader::SlotRange;

const char* kind_name(SlotKind kind) {
  switch (kind) {
    case SlotKind::Uniform: return "uniform";
    case SlotKind::Storage: return "storage";
    case SlotKind::Texture: return "texture";
    case SlotKind::Image: return "image";
  }
  return "?";
}

using lucent::test::read_text;

// A slot found in a source file.
struct Found {
  std::string name, file;
  SlotKind kind;
  int index;
  std::string comment;  // the rest of the line: a slot another pass of the same owner also binds says so there
};

// Which pass-local range a file's slots must lie in: by the folder that owns them.
std::string owner_group(const std::string& file) {
  if (file.find("src/methods/") != std::string::npos) return "method";
  if (file.find("src/geometry/") != std::string::npos || file.find("shaders/geometry/") != std::string::npos)
    return "isosurface";
  if (file.find("texture_space") != std::string::npos) return "texture-space";
  if (file.find("src/denoise/") != std::string::npos || file.find("shaders/denoise/") != std::string::npos)
    return "denoise";
  return "";
}

std::vector<Found> scan_sources() {
  std::vector<Found> found;
  const std::regex define(R"(#define\s+(LUCENT_(BINDING|TEX|IMAGE)_\w+)\s+(\d+)(.*))");
  const std::regex constant(R"(constexpr\s+int\s+(k(Binding|Texture|Image)\w*)\s*=\s*(\d+)\s*;(.*))");
  for (const char* root : {"src", "shaders"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(LUCENT_SOURCE_DIR) / root)) {
      if (!entry.is_regular_file()) continue;
      const std::string file = fs::relative(entry.path(), LUCENT_SOURCE_DIR).string();
      if (file == "src/shared/bindings.h") continue;
      std::istringstream lines(read_text(entry.path()));
      for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (std::regex_search(line, m, define) || std::regex_search(line, m, constant)) {
          const std::string what = m[2];
          const std::string comment = m[4];
          SlotKind kind = SlotKind::Storage;
          if (what == "TEX" || what == "Texture") kind = SlotKind::Texture;
          else if (what == "IMAGE" || what == "Image") kind = SlotKind::Image;
          else if (comment.find("uniform") != std::string::npos) kind = SlotKind::Uniform;
          found.push_back({m[1], file, kind, std::stoi(m[3]), comment});
        }
      }
    }
  return found;
}

// The group a range belongs to: its name's first word ("method images" -> "method").
std::string group_of(const SlotRange& r) {
  const std::string name = r.name;
  return name.substr(0, name.find(' '));
}

// Two ranges of one kind never overlap, unless one runs only after the other's group (runs_after): the denoising
// stage's images reuse the method's. A frame slot is never shared.
TEST(Bindings, RangesOfOneKindNeverOverlap) {
  for (const SlotRange& a : lucent::shader::kSlotTable) {
    EXPECT_LE(a.first, a.last) << a.name;
    for (const SlotRange& b : lucent::shader::kSlotTable) {
      if (&a == &b || a.kind != b.kind) continue;
      const bool sequential = !a.frame && !b.frame && ((a.runs_after && group_of(b) == a.runs_after) ||
                                                       (b.runs_after && group_of(a) == b.runs_after));
      if (sequential) continue;
      EXPECT_TRUE(a.last < b.first || b.last < a.first)
          << kind_name(a.kind) << " slots overlap: " << a.name << " [" << a.first << ", " << a.last << "] and "
          << b.name << " [" << b.first << ", " << b.last << "]";
    }
  }
}

TEST(Bindings, FitGuaranteedLimits) {
  const std::map<SlotKind, int> limit = {{SlotKind::Uniform, lucent::shader::kMaxUniformBinding},
                                         {SlotKind::Storage, lucent::shader::kMaxStorageBinding},
                                         {SlotKind::Texture, lucent::shader::kMaxTextureUnit},
                                         {SlotKind::Image, lucent::shader::kMaxImageUnit}};
  for (const SlotRange& r : lucent::shader::kSlotTable) {
    EXPECT_GE(r.first, 0) << r.name;
    EXPECT_LE(r.last, limit.at(r.kind)) << r.name;
  }
}

// Every frame slot of the table is a #define of bindings.h with the same value, and every #define there is in
// the table (or is a range bound).
TEST(Bindings, TableMatchesTheHeader) {
  const std::string header = read_text(fs::path(LUCENT_SOURCE_DIR) / "src/shared/bindings.h");
  const std::regex define(R"(#define\s+(LUCENT_(?:BINDING|TEX|IMAGE)_\w+)\s+(\d+))");
  std::set<std::string> in_table;
  for (const SlotRange& r : lucent::shader::kSlotTable) in_table.insert(r.name);
  int defines = 0;
  for (std::sregex_iterator it(header.begin(), header.end(), define), end; it != end; ++it, ++defines)
    EXPECT_TRUE(in_table.count((*it)[1]) || std::string((*it)[1]) == "LUCENT_BINDING_PARITY")
        << (*it)[1] << " is defined in bindings.h but not listed in kSlotTable";
  EXPECT_GE(defines, 15);
}

TEST(Bindings, EverySlotInTheSourcesIsInsideItsOwnersRange) {
  const std::vector<Found> found = scan_sources();
  ASSERT_GE(found.size(), 30u) << "the scan found too few slots; did the sources move?";
  std::map<std::string, std::string> range_group = {
      {"method uniform", "method"}, {"method storage", "method"}, {"method textures", "method"},
      {"method images", "method"}, {"isosurface uniform", "isosurface"}, {"isosurface storage", "isosurface"},
      {"texture-space storage", "texture-space"}, {"texture-space textures", "texture-space"},
      {"texture-space images", "texture-space"}, {"denoise uniform", "denoise"}, {"denoise textures", "denoise"},
      {"denoise images", "denoise"}};
  for (const Found& f : found) {
    if (f.name == "LUCENT_ISO_MAX_BINDING") continue;  // a bound, not a slot
    const std::string group = owner_group(f.file);
    bool inside = false;
    for (const SlotRange& r : lucent::shader::kSlotTable)
      if (r.kind == f.kind && !r.frame && range_group[r.name] == group && f.index >= r.first && f.index <= r.last)
        inside = true;
    EXPECT_TRUE(inside) << f.file << ": " << f.name << " = " << f.index << " (" << kind_name(f.kind)
                        << ") is outside the " << (group.empty() ? "(no owner)" : group)
                        << " range of src/shared/bindings.h";
  }
  // Within one owner folder, two slots of one kind never share an index, unless the later one declares that it
  // shares the slot with the other ("shares slot N with LUCENT_..."): two passes that never run together.
  std::map<std::tuple<std::string, SlotKind, int>, std::string> used;
  for (const Found& f : found) {
    if (f.name == "LUCENT_ISO_MAX_BINDING") continue;
    const std::string folder = fs::path(f.file).parent_path().string();
    auto key = std::make_tuple(folder.substr(folder.find('/') + 1), f.kind, f.index);
    auto [it, fresh] = used.emplace(key, f.name);
    const bool declared = f.comment.find("shares slot " + std::to_string(f.index) + " with " + it->second) !=
                          std::string::npos;
    EXPECT_TRUE(fresh || it->second == f.name || declared)
        << f.file << ": " << f.name << " and " << it->second << " are both " << kind_name(f.kind) << " slot " << f.index;
  }
}

// Passes bind named slots only: a literal number would escape the table.
TEST(Bindings, NoPassBindsALiteralSlot) {
  const std::regex literal(R"((glBindTextureUnit\(\s*\d|glBindImageTexture\(\s*\d|glBindBufferBase\(\s*GL_\w+,\s*\d|binding\s*=\s*\d))");
  for (const char* root : {"src", "shaders"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(LUCENT_SOURCE_DIR) / root)) {
      if (!entry.is_regular_file()) continue;
      const std::string text = read_text(entry.path());
      std::smatch m;
      EXPECT_FALSE(std::regex_search(text, m, literal))
          << fs::relative(entry.path(), LUCENT_SOURCE_DIR).string() << ": binds a literal slot: " << m.str();
    }
}

}  // namespace
