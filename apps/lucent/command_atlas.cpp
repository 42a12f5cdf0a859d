// command_atlas.cpp: `lucent atlas [MESH_OR_SCENE]`: the texture atlas of a mesh file or of a scene's translucent
// objects (src/texture_space/): chart count, utilization, stretch and build time, and optionally a picture of it.
// The atlas goes through the precompute cache ("(cached)" after the build time when it was read back; --no-cache).
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "lucent/lucent.h"
#include "option_checks.h"
#include "texture_space/scene_atlas_cache.h"
#include "texture_space/uv_raster.h"

namespace lucent::cli {
namespace {

struct AtlasCommandOptions {
  std::string input;  // mesh file or scene (.json); the built-in default scene when empty
  std::string png;
  int size = texture_space::AtlasOptions{}.size;
  float cone_deg = texture_space::AtlasOptions{}.cone_deg;  // [degrees]
  bool json = false;
  bool charts = false;
};

// A mesh file becomes a scene of one translucent object (the material only marks it translucent).
Scene input_scene(const std::string& input) {
  if (input.empty()) return default_scene();
  if (lowercase_extension(input) == ".json") return load_scene(input);
  Scene scene;
  scene.source = input;
  SceneObject object;
  object.name = std::filesystem::path(input).filename().string();
  object.mesh = load_mesh(input);
  object.mesh_file = input;
  object.material = Material{};
  scene.objects.push_back(std::move(object));
  return scene;
}

// Distinct, fairly bright colours for consecutive chart ids (golden-ratio hue steps).
std::array<std::uint8_t, 3> chart_colour(std::uint32_t chart) {
  double h = std::fmod(0.618033988749895 * chart, 1.0) * 6.0, s = 0.65, v = 0.95 - 0.25 * ((chart / 7) % 2);
  double c = v * s, x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0)), m = v - c;
  double rgb[6][3] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  const double* p = rgb[static_cast<int>(h) % 6];
  auto byte = [&](double channel) { return static_cast<std::uint8_t>(std::lround(255.0 * (channel + m))); };
  return {byte(p[0]), byte(p[1]), byte(p[2])};
}

// Texels whose centre lies in a chart's triangle in its colour, the rest dark; v = 0 at the bottom row.
ImageRGBA8 draw_atlas(const texture_space::Atlas& atlas) {
  const int n = atlas.size;
  ImageRGBA8 image{n, n, std::vector<std::uint8_t>(4 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 255)};
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) image.pixels[i] = 18, image.pixels[i + 1] = 18, image.pixels[i + 2] = 22;
  for (const texture_space::AtlasObject& object : atlas.objects)
    for (std::size_t f = 0; f < object.chart.size(); ++f) {
      const TriangleMesh& m = object.mesh;
      std::array<std::uint8_t, 3> colour = chart_colour(object.chart[f]);
      texture_space::for_each_cell_inside(m.uvs[m.indices[3 * f]], m.uvs[m.indices[3 * f + 1]], m.uvs[m.indices[3 * f + 2]], n,
                                          -1e-9, [&](int x, int y) {
                                            std::uint8_t* p = image.at(x, n - 1 - y);
                                            p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
                                          });
    }
  return image;
}

void run(const AtlasCommandOptions& o) {
  Scene scene = input_scene(o.input);
  const std::vector<OutputPath> outputs = {{o.png, "--output", {".png"}}};
  check_outputs(outputs, scene_input_files(scene));
  const OutputLock lock(outputs);
  texture_space::AtlasOptions options;
  options.size = o.size;
  options.cone_deg = o.cone_deg;
  options.use_own_uvs = !o.charts;
  texture_space::CachedSceneAtlas cached = texture_space::load_or_build_scene_atlas(scene, options);
  const texture_space::SceneAtlas& result = cached.atlas;
  const texture_space::AtlasMetrics& m = result.atlas.metrics;
  std::size_t triangles = 0;
  for (const texture_space::AtlasObject& object : result.atlas.objects) triangles += object.chart.size();
  if (!o.png.empty()) write_png(o.png, draw_atlas(result.atlas));
  if (o.json) {
    nlohmann::json objects = nlohmann::json::array();
    for (std::size_t i : result.object_index) objects.push_back(scene.objects[i].name);
    nlohmann::json out = {{"input", scene.source},           {"objects", objects},
                          {"triangles", triangles},          {"size", o.size},
                          {"cone_deg", o.cone_deg},          {"own_uvs", result.own_uvs},
                          {"charts", m.chart_count},         {"utilization", m.utilization},
                          {"stretch_l2", m.stretch_l2},      {"stretch_max", m.stretch_max},
                          {"angle_mean", m.angle_mean},      {"angle_max", m.angle_max},
                          {"texel_size", m.texel_size},      {"build_ms", m.build_ms},
                          {"cached", cached.from_cache}};
    if (!result.own_uv_problem.empty()) out["own_uv_problem"] = result.own_uv_problem;
    fmt::print("{}\n", out.dump(2));
    return;
  }
  fmt::print("{}: {} translucent object(s), {} triangles, atlas {} x {} texels{}\n", scene.source,
             result.object_index.size(), triangles, o.size, o.size, o.png.empty() ? "" : " -> " + o.png);
  if (!result.own_uv_problem.empty()) fmt::print("  own texture coordinates not used: {}\n", result.own_uv_problem);
  fmt::print("  charts            {}{}\n", m.chart_count, result.own_uvs ? " (the mesh's own texture coordinates)" : "");
  fmt::print("  utilization       {:.3f} of the texels\n", m.utilization);
  fmt::print("  stretch (area)    L2 {:.4f}, max {:.4f}\n", m.stretch_l2, m.stretch_max);
  fmt::print("  stretch (angle)   mean {:.4f}, max {:.4f}\n", m.angle_mean, m.angle_max);
  fmt::print("  texel size        {:.4g} scene units\n", m.texel_size);
  fmt::print("  build time        {:.1f} ms{}\n", m.build_ms, cached.from_cache ? " (cached)" : "");
}

}  // namespace

void add_atlas_command(CLI::App& app) {
  auto options = std::make_shared<AtlasCommandOptions>();
  CLI::App* cmd = app.add_subcommand("atlas", "build the texture atlas of a mesh or of a scene's translucent objects");
  cmd->add_option("input", options->input, "mesh file or scene (.json); the built-in default scene when omitted");
  cmd->add_option("--size", options->size, "atlas width and height [texels]")->check(whole_number_in(16, 16384, "texels"))->capture_default_str();
  cmd->add_option("--cone", options->cone_deg, "half-angle of the cone holding each chart's normals [degrees]")
      ->check(number_in(1, 89, false, "degrees"))->capture_default_str();
  cmd->add_flag("--json", options->json, "print JSON");
  cmd->add_flag("--charts", options->charts, "build charts even where a single mesh's own texture coordinates are usable");
  cmd->add_option("-o,--output", options->png, "draw the atlas to a PNG: charts in colours, empty texels dark");
  add_no_cache_flag(cmd);
  cmd->callback([options] { run(*options); });
}

}  // namespace lucent::cli
