// test_hostile_json.cpp: hostile JSON input gives one error line naming the input, never a crash or an "internal
// error": nesting 100,000 levels deep (in a scene file, a --set value, a --set key path, a bench configuration),
// duplicate keys (in every JSON input), numbers beyond double or float, values of the wrong type where a string is
// read, and huge values echoed in messages. An error in a value set by --set names the --set argument. Degenerate
// scenes are refused (a camera whose up is its view direction, vertices beyond float precision) and a translucent
// scene without a light warns.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "../test_support.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/mesh.h"
#include "lucent/medium_volume.h"
#include "lucent/scene.h"
#include "methods/method_info.h"
#include "params/param_json.h"
#include "../test_paths.h"

namespace lucent {
namespace {

using nlohmann::json;

constexpr const char* kSource = "test.json";
constexpr std::size_t kDeep = 100000;  // levels of nesting; 60,000 overflowed the stack before the depth limit

// A small valid scene: one translucent sphere, one light.
json minimal_scene() {
  return json{
      {"lights", json::array({json{{"direction", {0.0, -1.0, 0.0}}}})},
      {"objects", json::array({json{{"shape", "sphere"}, {"material", "Marble"}}})},
  };
}

std::string text_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return test::error_message([&] { parse_scene(text, kSource, ".", overrides); });
}

std::string scene_error(const json& doc, const std::vector<std::string>& overrides = {}) {
  return text_error(doc.dump(), overrides);
}

std::string repeat(const std::string& text, std::size_t times) {
  std::string out;
  for (std::size_t i = 0; i < times; ++i) out += text;
  return out;
}

std::string deep_array(std::size_t levels) { return std::string(levels, '[') + std::string(levels, ']'); }

// `prefix` followed by "/0" to make a JSON pointer `levels` arrays deep, cut to the 60 characters messages show.
std::string deep_pointer_excerpt(const std::string& prefix, std::size_t levels) {
  std::string pointer = prefix;
  for (std::size_t i = 0; i < levels; ++i) pointer += "/0";
  return pointer.substr(0, 57) + "...";
}

std::filesystem::path hostile_dir() {
  auto dir = std::filesystem::path(::testing::TempDir()) / "lucent_hostile_json";
  std::filesystem::create_directories(dir);
  return dir;
}

std::string write_file(const std::string& name, const std::string& text) {
  std::string path = (hostile_dir() / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// ---- the reader itself ----------------------------------------------------------------------------------------------

TEST(HostileJson, ExcerptsCutValuesAndText) {
  EXPECT_EQ(excerpt(json{{"a", 1}}), "{\"a\":1}");
  EXPECT_EQ(excerpt(json(std::string(100, 'x'))), "\"" + std::string(56, 'x') + "...");
  EXPECT_EQ(excerpt(json(std::string("\xff"))), "\"\xef\xbf\xbd\"");  // invalid UTF-8 replaced, not thrown
  EXPECT_EQ(text_excerpt("a\nb"), "a b");
  // Never cut inside a UTF-8 sequence: 56 ASCII bytes, then a 2-byte character straddling the cut.
  EXPECT_EQ(text_excerpt(std::string(56, 'a') + "\xc3\xa9" + std::string(10, 'b')), std::string(56, 'a') + "...");
}

TEST(HostileJson, DepthLimitIsExactAndCountsTheEnclosingPointer) {
  EXPECT_NO_THROW(parse_json(deep_array(kMaxJsonDepth), {"a.json", ""}));
  EXPECT_EQ(test::error_message([] { parse_json(deep_array(kMaxJsonDepth + 1), {"a.json", ""}); }),
            "a.json: " + deep_pointer_excerpt("", 128) + ": nested deeper than 128 levels");
  // A value placed at /x/y sits inside two levels already.
  EXPECT_NO_THROW(parse_json(deep_array(kMaxJsonDepth - 2), {"a.json", "/x/y"}));
  EXPECT_EQ(test::error_message([] { parse_json(deep_array(kMaxJsonDepth - 1), {"a.json", "/x/y"}); }),
            "a.json: " + deep_pointer_excerpt("/x/y", 126) + ": nested deeper than 128 levels");
}

TEST(HostileJson, TryParseDiscardsSyntaxErrorsButNotLimits) {
  EXPECT_TRUE(try_parse_json("not json", {"a", ""}).is_discarded());
  EXPECT_EQ(try_parse_json("[1, 2]", {"a", ""}), json({1, 2}));
  EXPECT_EQ(test::error_message([] { try_parse_json(R"({"k": 1, "k": 2})", {"a", ""}); }),
            "a: /k: duplicate key (each key may appear once in an object)");
  EXPECT_EQ(test::error_message([] { try_parse_json("1e999", {"a", ""}); }),
            "a: malformed JSON: line 1, column 5: number overflow parsing '1e999'");
}

TEST(HostileJson, LineAndColumnCountFromTheText) {
  EXPECT_EQ(test::error_message([] { parse_json("// comment\n{\n\n   \"a\": x}", {"a.json", ""}); }),
            "a.json: malformed JSON: line 4, column 9: syntax error while parsing value - invalid literal; last read: "
            "'\"a\": x'");
  EXPECT_EQ(test::error_message([] { parse_json("", {"a.json", ""}); }),
            "a.json: malformed JSON: line 1, column 1: syntax error while parsing value - unexpected end of input; "
            "expected '[', '{', or a literal");
  // Keys that need escaping in a JSON pointer are shown as they are.
  EXPECT_EQ(test::error_message([] { parse_json(R"({"a/b": 1, "a/b": 2})", {"a.json", ""}); }),
            "a.json: /a/b: duplicate key (each key may appear once in an object)");
}

// The seeds of the scene fuzzer are hostile inputs: each is one error line, never a crash.
TEST(HostileJson, FuzzSeedsAreOneLineErrors) {
  // The hostile seeds of the scene fuzzer's corpus (the others are valid scenes that reach the loaders).
  const auto corpus = std::filesystem::path(LUCENT_TEST_DATA).parent_path() / "fuzz" / "corpus" / "scene";
  for (const char* name : {"deep_nesting.json", "duplicate_keys.json", "number_overflow.json", "non_string_name.json"}) {
    std::ifstream in(corpus / name, std::ios::binary);
    ASSERT_TRUE(in) << name;
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::string message = test::error_message([&] { parse_scene(text, name, ".", {}); });
    EXPECT_FALSE(message.empty()) << name;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// ---- nesting depth --------------------------------------------------------------------------------------------------

TEST(HostileJson, DeepNestingInASceneFileIsAnError) {
  // The root object is level 1 and "comment" level 2, so level 129 is 127 arrays below /comment.
  EXPECT_EQ(text_error(R"({"comment": )" + deep_array(kDeep) + "}"),
            "test.json: " + deep_pointer_excerpt("/comment", 127) + ": nested deeper than 128 levels");
}

TEST(HostileJson, DeepNestingInASetValueIsAnError) {
  const std::string assignment = "method=" + deep_array(kDeep);
  EXPECT_EQ(scene_error(minimal_scene(), {assignment}),
            "--set '" + assignment.substr(0, 57) + "...': " + deep_pointer_excerpt("/method", 127) +
                ": nested deeper than 128 levels");
}

TEST(HostileJson, DeepSetKeyPathIsAnError) {
  std::string assignment = "render";
  for (std::size_t i = 0; i < kDeep; ++i) assignment += ".a";
  assignment += "=1";
  EXPECT_EQ(scene_error(minimal_scene(), {assignment}),
            "--set '" + assignment.substr(0, 57) + "...': key path deeper than 128 levels");
}

TEST(HostileJson, NestingUpToTheLimitIsAccepted) {
  // The root object (level 1) and the "comment" array (level 2) leave 126 levels for the arrays inside.
  EXPECT_EQ(text_error(R"({"comment": )" + deep_array(127) + "}"),
            "test.json: /comment: expected a string, got " + std::string(57, '[') + "...");
}

// ---- duplicate keys, numbers, types, excerpts -----------------------------------------------------------------------

TEST(HostileJson, DuplicateKeysAreErrors) {
  EXPECT_EQ(text_error(R"({"objects": [{"shape": "sphere", "material": "Marble"}],
                            "render": {"width": 10, "width": 20}})"),
            "test.json: /render/width: duplicate key (each key may appear once in an object)");
  EXPECT_EQ(text_error(R"({"objects": [{"shape": "sphere", "material": "Marble"}],
                            "objects": [{"shape": "box", "material": "Marble"}]})"),
            "test.json: /objects: duplicate key (each key may appear once in an object)");
  EXPECT_EQ(text_error(R"({"objects": [{"shape": "sphere", "material": {"preset": "Marble", "preset": "Skin1"}}]})"),
            "test.json: /objects/0/material/preset: duplicate key (each key may appear once in an object)");
}

TEST(HostileJson, NumberOverflowNamesLineAndColumn) {
  EXPECT_EQ(text_error("{\"render\": {\n  \"exposure\": 1e999}}"),
            "test.json: malformed JSON: line 2, column 19: number overflow parsing '1e999'");
}

TEST(HostileJson, MalformedJsonNamesLineAndColumn) {
  EXPECT_EQ(text_error("{\"objects\": [\n  {\"shape\": \"sphere\",,}]}"),
            "test.json: malformed JSON: line 2, column 22: syntax error while parsing object key - unexpected ','; "
            "expected string literal");
}

TEST(HostileJson, UnterminatedHugeStringIsExcerpted) {
  EXPECT_EQ(text_error("{\"comment\": \"" + std::string(100000, 'a')),
            "test.json: malformed JSON: line 1, column 100014: syntax error while parsing value - invalid string: "
            "missing closing quote; last read: '\"" + std::string(55, 'a') + "...");
}

TEST(HostileJson, NonStringMethodNameIsATypeError) {
  json doc = minimal_scene();
  doc["method"] = {{"name", 3}};
  EXPECT_EQ(scene_error(doc), "test.json: /method/name: expected a string, got 3");
}

TEST(HostileJson, ProfileNumbersBeyondFloatAreErrors) {
  json doc = minimal_scene();
  doc["objects"][0] = {{"shape", "lathe"}, {"profile", {{1e300, 0}, {1, 0}, {1, 1}}}, {"material", "Marble"}};
  EXPECT_EQ(scene_error(doc), "test.json: /objects/0/profile/0: [1e+300, 0]: r must be >= 0 and both finite");
}

TEST(HostileJson, HugeValuesAreExcerptedInMessages) {
  json doc = minimal_scene();
  doc["render"] = {{"width", std::vector<int>(20000, 7)}};
  EXPECT_EQ(scene_error(doc),
            "test.json: /render/width: expected a number, got [" + repeat("7,", 28) + "...");
  doc = minimal_scene();
  doc["method"] = {{"name", std::string(20000, 'x')}};
  std::string known;  // every registered method, in registry order
  for (const lucent::methods::MethodInfo* m : lucent::methods::method_registry())
    known += (known.empty() ? "" : ", ") + std::string(m->name);
  EXPECT_EQ(scene_error(doc), "test.json: /method/name: unknown method '" + std::string(57, 'x') + "...'; known: " + known);
  doc = minimal_scene();
  doc[std::string(20000, 'k')] = 1;
  EXPECT_EQ(scene_error(doc).substr(0, 84), "test.json: /" + std::string(56, 'k') + "...: unknown key");
}

TEST(HostileJson, InvalidUtf8SetValueIsReportedNotThrown) {
  // A --set value that is not JSON is a bare string; its bytes need not be UTF-8.
  EXPECT_EQ(scene_error(minimal_scene(), {"render.width=\xff"}),
            "--set 'render.width=\xff': /render/width: expected a number, got \"\xef\xbf\xbd\"");
}

// ---- --set errors name the --set argument ---------------------------------------------------------------------------

TEST(HostileJson, SetErrorsNameTheSetArgument) {
  EXPECT_EQ(scene_error(minimal_scene(), {"render.width=10", "method.K=0"}),
            "--set 'method.K=0': /method/K: 0 is out of range; allowed range [1, 64] maps");
  EXPECT_EQ(scene_error(minimal_scene(), {"objects.0.material={\"preset\": \"Nope\"}"}),
            "--set 'objects.0.material={\"preset\": \"Nope\"}': /objects/0/material/preset: unknown material 'Nope' "
            "(see: lucent materials)");
  EXPECT_EQ(scene_error(minimal_scene(), {"method.KK=1"}).substr(0, 44), "--set 'method.KK=1': /method/KK: unknown key");
  // The later of two overrides of the same key is the one in effect.
  EXPECT_EQ(scene_error(minimal_scene(), {"render.width=0", "render.width=-1"}),
            "--set 'render.width=-1': /render/width: -1 is out of range; allowed range [1, 16384] pixels");
  // Errors elsewhere still name the scene file.
  json doc = minimal_scene();
  doc["method"] = {{"K", 0}};
  EXPECT_EQ(scene_error(doc, {"render.width=10"}), "test.json: /method/K: 0 is out of range; allowed range [1, 64] maps");
  EXPECT_EQ(scene_error(minimal_scene(), {"render.exposure=1e999"}),
            "--set 'render.exposure=1e999': malformed JSON: line 1, column 5: number overflow parsing '1e999'");
}

// ---- degenerate and absurd scenes -----------------------------------------------------------------------------------

TEST(HostileJson, CameraUpAlongTheViewDirectionIsAnError) {
  json doc = minimal_scene();
  doc["camera"] = {{"eye", {0, 5, 0}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}}};
  EXPECT_EQ(scene_error(doc), "test.json: /camera/up: parallel to the view direction from eye to target");
  doc["camera"]["up"] = {0, -1, 0};
  EXPECT_EQ(scene_error(doc), "test.json: /camera/up: parallel to the view direction from eye to target");
  doc["camera"]["up"] = {0, 0, 1};
  EXPECT_EQ(scene_error(doc), "");
}

TEST(HostileJson, MeshBeyondFloatPrecisionIsAnError) {
  const std::string mesh = write_file("far.obj", "v 1e30 0 0\nv 0 1e30 0\nv 0 0 1e30\nf 1 2 3\n");
  json doc = minimal_scene();
  doc["objects"][0] = {{"mesh", mesh}, {"albedo", {0.5, 0.5, 0.5}}};
  EXPECT_EQ(scene_error(doc),
            "test.json: /objects/0: vertex 0 is at (1e+30, 0, 0) in world space, beyond 1e+07 scene units "
            "(float precision)");
  doc["objects"][0] = {{"shape", "box"}, {"translate", {2e7, 0, 0}}, {"material", "Marble"}};
  EXPECT_EQ(scene_error(doc),
            "test.json: /objects/0: vertex 0 is at (2e+07, -0.5, -0.5) in world space, beyond 1e+07 scene units "
            "(float precision)");
  doc["objects"][0] = {{"shape", "box"}, {"translate", {9e6, 0, 0}}, {"material", "Marble"}};
  EXPECT_EQ(scene_error(doc), "");
}

TEST(HostileJson, TranslucentSceneWithoutLightWarns) {
  json doc = minimal_scene();
  doc.erase("lights");
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(scene_error(doc), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "lucent: warning: test.json: translucent objects but no light (lights, environment); the image will be "
            "black\n");
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(scene_error(minimal_scene()), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// ---- other JSON inputs ----------------------------------------------------------------------------------------------

TEST(HostileJson, VolumeHeaderDuplicateKeyIsAnError) {
  const std::string header = write_file("volume.json", R"({"size": [1, 1, 1], "data": "a.raw", "data": "b.raw"})");
  EXPECT_EQ(test::error_message([&] { load_medium_volume(header); }),
            header + ": /data: duplicate key (each key may appear once in an object)");
}

TEST(HostileJson, BenchConfigurationMalformedNamesLineAndColumn) {
  const std::string config = write_file("bench_malformed.json", "{\"runs\": [\n  {\"scene\": \"a.json\"\n]}");
  auto r = test::run_cli("bench " + config + " -o " + (hostile_dir() / "bench_out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + config +
                          ": malformed JSON: line 3, column 1: syntax error while parsing object - unexpected ']'; "
                          "expected '}'\n");
}

TEST(HostileJson, BenchConfigurationDuplicateKeyAndDepth) {
  const std::string duplicate =
      write_file("bench_duplicate.json", R"({"runs": [{"scene": "/nonexistent/a.json", "scene": "/nonexistent/b.json"}]})");
  auto r = test::run_cli("bench " + duplicate + " -o " + (hostile_dir() / "bench_out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + duplicate + ": /runs/0/scene: duplicate key (each key may appear once in an object)\n");
  const std::string deep = write_file("bench_deep.json", R"({"description": )" + deep_array(kDeep) + "}");
  r = test::run_cli("bench " + deep + " -o " + (hostile_dir() / "bench_out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + deep + ": " + deep_pointer_excerpt("/description", 127) +
                          ": nested deeper than 128 levels\n");
}

TEST(HostileJson, SceneFileAndSetThroughTheCli) {
  const std::string scene = write_file("cli_scene.json", R"({"comment": )" + deep_array(kDeep) + "}");
  auto r = test::run_cli("reference " + scene);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + scene + ": " + deep_pointer_excerpt("/comment", 127) +
                          ": nested deeper than 128 levels\n");
  const std::string good = write_file("cli_good.json", minimal_scene().dump());
  r = test::run_cli("reference " + good + " --set method.K=0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: --set 'method.K=0': /method/K: 0 is out of range; allowed range [1, 64] maps\n");
  r = test::run_cli("reference " + good + " --set 'method={\"name\": 3}'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: --set 'method={\"name\": 3}': /method/name: expected a string, got 3\n");
}

// A NUL byte (JSON "\u0000") would cut a path where the operating system takes it: "sky.hdr\u0000.exr" would open
// sky.hdr after the extension check saw .exr. Every path the scene names is refused, naming its key.
TEST(HostileJson, PathsWithANulByteAreRefused) {
  const std::string scenes = LUCENT_SCENES_DIR;
  const std::string problem = "the file path holds a NUL byte (byte {}), which no file name can";
  auto expected = [&](const std::string& pointer, const std::string& path) {
    return std::string(kSource) + ": " + pointer + ": " +
           fmt::format(fmt::runtime(problem), path.find('\0'));
  };
  json doc = minimal_scene();
  std::string mesh = scenes + "/volumes/strata.json";
  mesh += std::string(1, '\0') + ".obj";
  doc["objects"][0] = json{{"mesh", mesh}, {"material", "Marble"}};
  EXPECT_EQ(scene_error(doc), expected("/objects/0/mesh", mesh));
  std::string map = scenes + "/maps/marble_albedo.png";
  map += std::string(1, '\0') + ".exr";
  doc = minimal_scene();
  doc["objects"][0]["material"] = json{{"preset", "Marble"}, {"albedo_map", map}};
  EXPECT_EQ(scene_error(doc), expected("/objects/0/material/albedo_map", map));
  std::string volume = scenes + "/volumes/strata.json";
  volume += std::string(1, '\0') + "x";
  doc = minimal_scene();
  doc["objects"][0]["material"] = json{{"preset", "Marble"}, {"field", {{"type", "volume"}, {"file", volume}}}};
  EXPECT_EQ(scene_error(doc), expected("/objects/0/material/field/file", volume));
  doc["objects"][0]["material"]["field"]["type"] = "vdb";
  EXPECT_EQ(scene_error(doc), expected("/objects/0/material/field/file", volume));
  std::string sky = scenes + "/env/sky.hdr";
  sky += std::string(1, '\0') + ".exr";
  doc = minimal_scene();
  doc["environment"] = json{{"file", sky}};
  EXPECT_EQ(scene_error(doc), expected("/environment/file", sky));
  // The readers refuse such paths too (the Python module hands strings to them as they are).
  EXPECT_EQ(test::error_message([&] { load_medium_volume(volume); }),
            scenes + "/volumes/strata.json\\x00x: " + fmt::format(fmt::runtime(problem), volume.find('\0')));
  EXPECT_EQ(test::error_message([&] { load_mesh(mesh); }),
            scenes + "/volumes/strata.json\\x00.obj: " + fmt::format(fmt::runtime(problem), mesh.find('\0')));
  EXPECT_EQ(test::error_message([&] { read_hdr(sky); }),
            scenes + "/env/sky.hdr\\x00.exr: " + fmt::format(fmt::runtime(problem), sky.find('\0')));
}

TEST(HostileJson, ReferenceMetadataDuplicateKeyIsAnError) {
  const std::string scene = write_file("ref_scene.json", minimal_scene().dump());
  const std::string meta = write_file("ref_resume.meta.json", R"({"samples_per_pixel": 2, "samples_per_pixel": 3})");
  const std::string exr = (hostile_dir() / "ref_resume.exr").string();
  auto r = test::run_cli("reference " + scene + " --resume -q -o " + exr);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + meta + ": /samples_per_pixel: duplicate key (each key may appear once in an object)\n");
}

}  // namespace
}  // namespace lucent
