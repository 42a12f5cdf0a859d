// test_output_safety.cpp: no output destroys an input or leaves a damaged file, write errors are errors, and
// command-line numbers are checked like scene values. Library calls (write_file, OutputSet, check_outputs) and the
// `lucent` tool from outside, on commands that need no GL context (render's output checks run before it makes one).
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "reference/reference_renderer.h"

#include "lucent/material.h"
#include "../cli_runner.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/output_file.h"

namespace {

namespace fs = std::filesystem;
using lucent::test::run_cli;

fs::path fresh_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / "lucent_output_safety" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void put(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Files in `dir` whose names mark them as lucent's temporaries.
int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    n += entry.path().filename().string().find(".lucent-tmp-") != std::string::npos;
  return n;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const lucent::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A small scene for the CPU reference (bssrdf integrator, 8x6 pixels).
std::string write_scene(const fs::path& path) {
  put(path, R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]}, "lights": [{"direction": [0, 0, -1]}],
    "objects": [{"shape": "sphere", "material": "Skin1"}], "render": {"width": 8, "height": 6}})");
  return path.string();
}

lucent::ImageRGBA32F gray_image(int width, int height, float value) {
  lucent::ImageRGBA32F image{width, height, std::vector<float>(4 * static_cast<std::size_t>(width) * height, value)};
  return image;
}

TEST(OutputFile, ReplacesTheFileAndLeavesNoTemporary) {
  const fs::path dir = fresh_dir("replace");
  const fs::path file = dir / "a.txt";
  put(file, "old");
  lucent::write_file(file.string(), "new contents");
  EXPECT_EQ(contents(file), "new contents");
  EXPECT_EQ(temporaries_in(dir), 0);
  const std::string missing = (dir / "sub" / "b.txt").string();  // folders are check_outputs' to create
  EXPECT_EQ(error_of([&] { lucent::write_file(missing, "x"); }), missing + ": cannot write: No such file or directory");
}

TEST(OutputFile, FollowsALinkAndReplacesItsTarget) {
  const fs::path dir = fresh_dir("link");
  put(dir / "target.txt", "old");
  fs::create_symlink("target.txt", dir / "link.txt");
  lucent::write_file((dir / "link.txt").string(), "new");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(contents(dir / "target.txt"), "new");
}

TEST(OutputFile, WriteErrorsAreErrors) {
  EXPECT_EQ(error_of([] { lucent::write_file("/dev/full", "x"); }), "/dev/full: cannot write: No space left on device");
  EXPECT_EQ(error_of([] { lucent::write_file("/dev/null", "x"); }), "(no error)");  // a device is written in place
  const fs::path dir = fresh_dir("errors");
  put(dir / "plain", "a file, not a folder");
  const std::string under_file = (dir / "plain" / "x.png").string();
  EXPECT_EQ(error_of([&] { lucent::write_file(under_file, "x"); }), under_file + ": cannot write: Not a directory");
  EXPECT_EQ(error_of([&] { lucent::write_file(dir.string(), "x"); }), dir.string() + ": cannot write: is a directory");
}

// A set is renamed only when every file of it was written: a failure on the last file leaves the first unchanged.
TEST(OutputFile, ASetIsWrittenWholeOrNotAtAll) {
  const fs::path dir = fresh_dir("set");
  put(dir / "mean.exr", "old mean");
  put(dir / "plain", "a file");
  lucent::OutputSet failing;
  failing.add((dir / "mean.exr").string(), "new mean");
  failing.add((dir / "plain" / "meta.json").string(), "{}");
  EXPECT_NE(error_of([&] { failing.commit(); }), "(no error)");
  EXPECT_EQ(contents(dir / "mean.exr"), "old mean");
  EXPECT_EQ(temporaries_in(dir), 0);
  lucent::OutputSet working;
  working.add((dir / "mean.exr").string(), "new mean");
  working.add((dir / "meta.json").string(), "{}");
  working.commit();
  EXPECT_EQ(contents(dir / "mean.exr"), "new mean");
  EXPECT_EQ(contents(dir / "meta.json"), "{}");
}

TEST(OutputFile, SameFileSeesThroughDotsAndLinks) {
  const fs::path dir = fresh_dir("same");
  put(dir / "s.json", "{}");
  fs::create_symlink("s.json", dir / "alias.json");
  EXPECT_TRUE(lucent::same_file((dir / "s.json").string(), (dir / "." / "s.json").string()));
  EXPECT_TRUE(lucent::same_file((dir / "s.json").string(), (dir / ".." / dir.filename() / "s.json").string()));
  EXPECT_TRUE(lucent::same_file((dir / "alias.json").string(), (dir / "s.json").string()));
  EXPECT_TRUE(lucent::same_file((dir / "new.png").string(), (dir / "." / "new.png").string()));  // neither exists
  EXPECT_FALSE(lucent::same_file((dir / "s.json").string(), (dir / "t.json").string()));
}

TEST(OutputFile, CheckOutputsRefusesInputsCollisionsFormatsAndUnwritableFolders) {
  const fs::path dir = fresh_dir("check");
  const std::string scene = (dir / "s.json").string();
  put(scene, "{}");
  using lucent::check_outputs;
  EXPECT_EQ(error_of([&] { check_outputs({{(dir / "." / "s.json").string(), "--output", {".png"}}}, {scene}); }),
            "--output " + (dir / "." / "s.json").string() + ": would overwrite the input " + scene +
                "; choose another output path");
  const std::string x = (dir / "x.png").string();
  EXPECT_EQ(error_of([&] { check_outputs({{x, "--output", {".png"}}, {x, "--exr", {".exr"}}}, {}); }),
            "--exr " + x + ": is also the output --output " + x + "; give each output its own path");
  const std::string jpg = (dir / "out.jpg").string();
  EXPECT_EQ(error_of([&] { check_outputs({{jpg, "--output", {".png"}}}, {}); }),
            "--output " + jpg + ": '.jpg' is not a format this command writes; use .png");
  EXPECT_EQ(error_of([&] { check_outputs({{(dir / "out").string(), "-o", {".hdr", ".exr"}}}, {}); }),
            "-o " + (dir / "out").string() + ": no file extension; use .hdr or .exr");
  EXPECT_EQ(error_of([&] { check_outputs({{(dir / "UPPER.PNG").string(), "-o", {".png"}}}, {}); }), "(no error)");
  const std::string under_file = (dir / "s.json" / "x.png").string();
  EXPECT_EQ(error_of([&] { check_outputs({{under_file, "-o", {".png"}}}, {}); }),
            "-o " + under_file + ": cannot create directory " + scene + ": Not a directory");
  EXPECT_EQ(error_of([&] { check_outputs({{"/dev/stdout", "-o", {".png"}}}, {}); }), "(no error)");
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_EQ(temporaries_in(dir), 0);  // the probe file is gone
}

// The metadata of `reference s.json -o s.exr` used to be s.json: the scene itself.
TEST(OutputSafetyCli, ReferenceMetadataNeverLandsOnTheScene) {
  const fs::path dir = fresh_dir("reference_meta");
  const std::string scene = write_scene(dir / "s.json");
  const std::string before = contents(scene);
  auto r = run_cli("reference " + scene + " --integrator bssrdf --spp 1 -q -o " + (dir / "s.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(contents(scene), before);
  EXPECT_TRUE(fs::exists(dir / "s.meta.json"));
  EXPECT_TRUE(fs::exists(dir / "s.stderr.exr"));
  EXPECT_EQ(temporaries_in(dir), 0);
  // Resuming reads the metadata back and adds samples.
  auto resumed = run_cli("reference " + scene + " --integrator bssrdf --spp 2 -q --resume -o " + (dir / "s.exr").string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(contents(dir / "s.meta.json").find("\"samples_per_pixel\": 3"), std::string::npos);
  EXPECT_EQ(contents(scene), before);
}

TEST(OutputSafetyCli, OutputsThatAreInputsAreRefusedAndLeftAlone) {
  const fs::path dir = fresh_dir("inputs");
  const std::string scene = write_scene(dir / "s.json");
  const std::string before = contents(scene);
  auto render_over_scene = run_cli("render " + scene + " -o " + scene);
  EXPECT_EQ(render_over_scene.exit_code, 1);
  EXPECT_EQ(render_over_scene.output,
            "lucent: --output " + scene + ": would overwrite the input " + scene + "; choose another output path\n");
  EXPECT_EQ(contents(scene), before);

  const std::string x = (dir / "x.png").string();
  auto both = run_cli("render " + scene + " -o " + x + " --exr " + x);
  EXPECT_EQ(both.output, "lucent: --exr " + x + ": is also the output --output " + x + "; give each output its own path\n");
  EXPECT_FALSE(fs::exists(x));

  const std::string jpg = (dir / "out.jpg").string();
  auto jpeg = run_cli("render " + scene + " -o " + jpg);
  EXPECT_EQ(jpeg.output, "lucent: --output " + jpg + ": '.jpg' is not a format this command writes; use .png or .exr\n");
  EXPECT_FALSE(fs::exists(jpg));

  const std::string exr = (dir / "a.exr").string();
  lucent::write_exr(exr, gray_image(4, 3, 0.5f));
  const std::string exr_before = contents(exr);
  auto tonemap = run_cli("tonemap " + exr + " -o " + exr);
  EXPECT_EQ(tonemap.exit_code, 1);
  EXPECT_EQ(tonemap.output, "lucent: --output " + exr + ": would overwrite the input " + exr +
                                "; choose another output path\n");
  EXPECT_EQ(contents(exr), exr_before);

  auto diff = run_cli("compare " + exr + " " + exr + " --diff " + exr);
  EXPECT_EQ(diff.output, "lucent: --diff " + exr + ": would overwrite the input " + exr + "; choose another output path\n");
  EXPECT_EQ(contents(exr), exr_before);
}

// A glTF mesh's external buffer and images are the scene's inputs as much as the mesh file: an output named like
// one of them is refused and the file is left as it was (the mesh would no longer load).
TEST(OutputSafetyCli, FilesAGltfMeshNamesAreInputs) {
  const fs::path dir = fresh_dir("gltf_inputs");
  // A tetrahedron: 4 float positions then 12 uint16 indices in buf.bin.
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::uint16_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof(positions));
  buffer.append(reinterpret_cast<const char*>(indices), sizeof(indices));
  put(dir / "buf.bin", buffer);
  lucent::write_png((dir / "tex.png").string(), lucent::ImageRGBA8{2, 2, std::vector<std::uint8_t>(16, 200)});
  put(dir / "mesh.gltf", R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
                  {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
    "buffers": [{"uri": "buf.bin", "byteLength": 72}], "images": [{"uri": "tex.png"}]})");
  put(dir / "s.json", R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]}, "lights": [{"direction": [0, 0, -1]}],
    "objects": [{"mesh": "mesh.gltf", "material": "Skin1"}], "render": {"width": 8, "height": 6}})");
  const std::string scene = (dir / "s.json").string();
  for (const std::string name : {"buf.bin", "tex.png"}) {
    const fs::path input = dir / name;
    const std::string before = contents(input);
    for (const std::string command : {"render", "reference"}) {
      auto r = run_cli(command + " " + scene + " -q -o '" + input.string() + "'");
      EXPECT_EQ(r.exit_code, 1) << command << " " << name;
      EXPECT_NE(r.output.find("would overwrite the input " + input.string()), std::string::npos) << r.output;
      EXPECT_EQ(contents(input), before) << command << " " << name;
    }
  }
}

// `render --animate -o maps/out.png` writes maps/out_0000.png, maps/out_0001.png, ...: every frame is checked against
// the scene's inputs before the first is written, not frame 0 alone (a texture named like frame 1 was replaced).
TEST(OutputSafetyCli, EveryAnimationFrameIsCheckedAgainstTheInputs) {
  const fs::path dir = fresh_dir("animate_inputs");
  fs::create_directories(dir / "maps");
  const std::string map = (dir / "maps" / "out_0001.png").string();
  lucent::write_png(map, lucent::ImageRGBA8{2, 2, std::vector<std::uint8_t>(16, 200)});
  const std::string map_before = contents(map);
  put(dir / "s.json", R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]}, "lights": [{"direction": [0, 0, -1]}],
    "objects": [{"shape": "sphere", "material": {"albedo_map": "maps/out_0001.png", "mfp_mm": 1}}],
    "render": {"width": 8, "height": 6}})");
  const std::string scene = (dir / "s.json").string(), png = (dir / "maps" / "out.png").string();
  auto r = run_cli("render " + scene + " --animate --frames 3 -q -o " + png);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: --output (frame 1) " + map + ": would overwrite the input " + map +
                          "; choose another output path\n");
  EXPECT_EQ(contents(map), map_before);
  EXPECT_FALSE(fs::exists(dir / "maps" / "out_0000.png"));  // nothing written before the check

}

// A reference fails on an output it cannot write before its first sample (the message is the check's, not the
// writer's after rendering), and writes nothing.
TEST(OutputSafetyCli, UnwritableOutputFolderIsFoundBeforeRendering) {
  const fs::path dir = fresh_dir("unwritable");
  const std::string scene = write_scene(dir / "s.json");
  put(dir / "plain", "a file where a folder is expected");
  const std::string output = (dir / "plain" / "ref.exr").string();
  auto r = run_cli("reference " + scene + " --integrator bssrdf --spp 64 -q -o " + output);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: --output " + output + ": cannot create directory " + (dir / "plain").string() +
                          ": Not a directory\n");
}

TEST(OutputSafetyCli, WriteErrorsFailTheCommandAndKeepTheOldFile) {
  const fs::path dir = fresh_dir("write_errors");
  const std::string exr = (dir / "big.exr").string(), png = (dir / "old.png").string();
  lucent::write_exr(exr, gray_image(256, 256, 0.25f));
  auto full = run_cli("tonemap " + exr + " -o /dev/full");
  EXPECT_EQ(full.exit_code, 1);
  EXPECT_EQ(full.output, "lucent: /dev/full: cannot write: No space left on device\n");

  // A file-size limit of 4 KiB (ulimit -f counts 512-byte blocks) stops the PNG part-way: a pattern that does not
  // compress to below the limit, unlike flat gray.
  lucent::ImageRGBA32F gradient = gray_image(256, 256, 0.0f);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      gradient.at(x, y)[0] = static_cast<float>((x * 37 + y * 101) % 256) / 255.0f;
      gradient.at(x, y)[1] = static_cast<float>((x * 13 + y * 7) % 256) / 255.0f;
    }
  lucent::write_exr(exr, gradient);
  put(png, "the old PNG");
  auto limited = run_cli("tonemap " + exr + " -o " + png, "ulimit -f 8;");
  EXPECT_EQ(limited.exit_code, 1);
  EXPECT_EQ(limited.output, "lucent: " + png + ": cannot write: File too large\n");
  EXPECT_EQ(contents(png), "the old PNG");
  EXPECT_EQ(temporaries_in(dir), 0);
}

TEST(OutputSafetyCli, CommandLineNumbersAreCheckedLikeSceneValues) {
  const fs::path dir = fresh_dir("numbers");
  const std::string exr = (dir / "a.exr").string();
  lucent::write_exr(exr, gray_image(4, 3, 0.5f));
  const std::string help = " (lucent --help lists the options)\n";
  const std::pair<std::string, std::string> cases[] = {
      {"tonemap " + exr + " -o " + (dir / "a.png").string() + " --exposure nan",
       "lucent: --exposure: nan is not a finite number; allowed range [-30, 30] stops" + help},
      {"compare " + exr + " " + exr + " --exposure inf",
       "lucent: --exposure: inf is not a finite number; allowed range [-30, 30] stops" + help},
      {"bssrdf --xo nan,0,0", "lucent: --xo: nan is not a finite number; allowed range [-1000000, 1000000] mm" + help},
      {"bssrdf --material Marble --xo 1e19,0,0",
       "lucent: --xo: 1e19 is out of range; allowed range [-1000000, 1000000] mm" + help},
      {"reference s.json --spp 1e0", "lucent: --spp: 1e0 is not a whole number (write digits only)" + help},
      {"slab --albedo 0.9 --photons 0x10", "lucent: --photons: '0x10' is not a number" + help},
      {"slab --albedo 0.9 --photons -5", "lucent: --photons: -5 is out of range; allowed range [1, 1000000000000]" + help},
      {"slab --albedo 0.9 --threads -3", "lucent: --threads: -3 is out of range; allowed range [0, 4096]" + help},
      {"slab --albedo 0.9 --photons 9223372036854775808",
       "lucent: --photons: 9223372036854775808 is out of range; allowed range [1, 1000000000000]" + help},
      {"slab --albedo 0.9 --photons 2.5", "lucent: --photons: 2.5 is not a whole number (write digits only)" + help},
      {"slab --albedo 0.9 --thickness nan", "lucent: --thickness: nan is not a finite number (write inf for a half-space)\n"},
      {"bssrdf --material Potato --sigma-a 1",
       "lucent: --material Potato: give either a preset or coefficients (--sigma-a, --sigma-s, --sigma-s-prime, --g), "
       "not both\n"},
      {"reference s.json --spp 0", "lucent: --spp: 0 is out of range; allowed range [1, 1000000000]" + help},
      {"render --seed -1", "lucent: --seed: -1 is out of range; allowed range [0, 4294967295]" + help},
      {"materials invert --albedo 0.5 --mfp 1.4427e303",
       "lucent: --mfp: 1.4427e303 is out of range; allowed range [-1e+30, 1e+30]" + help},
      {"materials invert --albedo nan --mfp 1", "lucent: --albedo: nan is not a finite number; allowed range [-1e+30, 1e+30]" + help},
  };
  for (const auto& [arguments, message] : cases) {
    auto r = run_cli(arguments);
    EXPECT_EQ(r.exit_code, 1) << arguments;
    EXPECT_EQ(r.output, message) << arguments;
  }
}

// Printed output is output too: a full disk behind stdout is an error, not exit 0 with the JSON lost.
TEST(OutputSafetyCli, StandardOutputWriteErrorsAreErrors) {
  for (const std::string arguments : {"materials", "slab --albedo 0.5 --photons 1000 --json"}) {
    auto r = run_cli(arguments, R"(sh -c 'exec "$0" "$@" > /dev/full')");  // stdout to /dev/full, stderr read here
    EXPECT_EQ(r.exit_code, 1) << arguments;
    EXPECT_EQ(r.output, "lucent: <stdout>: cannot write: No space left on device\n") << arguments;
  }
}

// -o /dev/stdout writes into whatever the shell opened (not a rename over the file it points to), in any format.
TEST(OutputSafetyCli, DevStdoutIsWrittenInPlace) {
  const fs::path dir = fresh_dir("stdout");
  const std::string exr = (dir / "a.exr").string(), png = (dir / "out.png").string();
  lucent::write_exr(exr, gray_image(4, 3, 0.5f));
  auto r = run_cli("tonemap " + exr + " -o /dev/stdout > " + png);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(lucent::read_png(png).width, 4);
}

TEST(OutputSafetyCli, LinksLongNamesAndResumingTheWrongReference) {
  const fs::path dir = fresh_dir("links");
  const std::string exr = (dir / "a.exr").string();
  lucent::write_exr(exr, gray_image(4, 3, 0.5f));
  fs::create_symlink("missing.png", dir / "dangling.png");  // a dangling link: its target is created
  ASSERT_EQ(run_cli("tonemap " + exr + " -o " + (dir / "dangling.png").string()).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.png"));
  EXPECT_EQ(lucent::read_png((dir / "missing.png").string()).width, 4);
  const std::string long_name = (dir / (std::string(250, 'x') + ".png")).string();  // 254 bytes: within NAME_MAX
  auto long_run = run_cli("tonemap " + exr + " -o " + long_name);
  EXPECT_EQ(long_run.exit_code, 0) << long_run.output;
  EXPECT_EQ(temporaries_in(dir), 0);

  const std::string scene = write_scene(dir / "s.json"), ref = (dir / "r.exr").string();
  ASSERT_EQ(run_cli("reference " + scene + " --integrator bssrdf --spp 1 -q -o " + ref).exit_code, 0);
  auto other_seed = run_cli("reference " + scene + " --integrator bssrdf --spp 1 --seed 7 -q --resume -o " + ref);
  EXPECT_EQ(other_seed.exit_code, 1);
  EXPECT_EQ(other_seed.output, "lucent: " + (dir / "r.meta.json").string() +
                                   ": cannot resume: the reference has seed 1, this run 7\n");
  auto other_integrator = run_cli("reference " + scene + " --integrator volpath --spp 1 -q --resume -o " + ref);
  EXPECT_EQ(other_integrator.output, "lucent: " + (dir / "r.meta.json").string() +
                                         ": cannot resume: the reference has integrator \"bssrdf\", this run \"volpath\"\n");
  put(dir / "r.meta.json", R"({"integrator": "bssrdf", "seed": 1, "samples_per_pixel": 2147483647, "reference_version": )" +
                            std::to_string(lucent::reference::kReferenceVersion) + R"(, )"
                            R"("models": ")" + std::string(lucent::to_string(lucent::kDefaultBssrdfModel)) + R"("})");
  auto overflow = run_cli("reference " + scene + " --integrator bssrdf --spp 1 -q --resume -o " + ref);
  EXPECT_EQ(overflow.output, "lucent: " + (dir / "r.meta.json").string() +
                                 ": cannot resume: 2147483647 + 1 samples per pixel exceed 2147483647\n");
}

TEST(OutputSafetyCli, CompareNamesBothFilesWhenSizesDiffer) {
  const fs::path dir = fresh_dir("compare_sizes");
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  lucent::write_exr(a, gray_image(4, 3, 0.5f));
  lucent::write_exr(b, gray_image(5, 3, 0.5f));
  auto r = run_cli("compare " + a + " " + b);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + a + " is 4x3 but " + b + " is 5x3; compare needs images of one size\n");
}

}  // namespace
