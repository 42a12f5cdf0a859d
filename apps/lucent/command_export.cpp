// command_export.cpp: `lucent export SCENE OUTPUT`: the scene as one glTF 2.0 file for other tools (Blender, glTF
// viewers), or as a scene file with its meshes beside it (save_scene_gltf and save_scene, lucent/scene_writer.h).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "lucent/scene_writer.h"

namespace lucent::cli {
namespace {

struct ExportOptions {
  std::string scene_path;
  std::string output;
  std::vector<std::string> sets;
};

void run_export(const ExportOptions& o) {
  const Scene scene = o.scene_path == "-" ? default_scene(o.sets) : load_scene(o.scene_path, o.sets);
  save_scene_as(scene, o.output);
  fmt::print("wrote {}\n", o.output);
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export", "write a scene as one glTF 2.0 file (.gltf, .glb: objects, materials, camera, lights; for Blender and "
                "glTF viewers) or as a scene file with its meshes (.json, as the viewer's \"save scene as\")");
  cmd->add_option("scene", options->scene_path, "scene file (JSON); - for the built-in default scene")->required();
  cmd->add_option("output", options->output, "output file: .gltf, .glb or .json")->required();
  cmd->add_option("--set", options->sets, "override a scene value, e.g. --set scale_mm=10 (as lucent render)");
  cmd->footer("\nglTF units: the objects sit under a node that scales scene units to metres (scale_mm / 1000);\n"
              "lights are KHR_lights_punctual at 683 lm/W (directional W/m^2 -> lux, point W/sr -> candela);\n"
              "materials keep their exact coefficients in extras.lucent (docs/materials.md, \"Whole-scene export\").");
  cmd->callback([options] { run_export(*options); });
}

}  // namespace lucent::cli
