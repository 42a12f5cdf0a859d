// command_envmap.cpp: `lucent envmap make|lights|error`: make the procedural environment maps, turn a map into
// directional lights for a scene file, and measure how well M lights reproduce a map's irradiance
// (docs/lights/environment.md).
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "commands.h"
#include "lucent/environment.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/output_file.h"

namespace lucent::cli {
namespace {

using lucent::EnvironmentMap;
using lucent::EnvironmentSampling;

// "sky", "gradient" and "constant" name the procedural maps (at `width`); anything else is a file.
EnvironmentMap map_named(const std::string& name, int width) {
  if (name == "sky") return lucent::make_sky_environment({.width = width});
  if (name == "gradient") return lucent::make_gradient_environment(width);
  if (name == "constant") return lucent::make_constant_environment(width, glm::vec3(1.0f));
  return lucent::load_environment_map(name);
}

void add_make_command(CLI::App& app) {
  static std::string kind = "sky", output;
  static int width = 256;
  CLI::App* cmd = app.add_subcommand("make", "write a procedural equirectangular map (.hdr or .exr)");
  cmd->add_option("kind", kind, "sky (gradient, sun, warm ground) or gradient")
      ->check(CLI::IsMember({"sky", "gradient"}));
  cmd->add_option("-o,--output", output, "output file, .hdr or .exr")->required();
  cmd->add_option("--width", width, "width in pixels (height = width / 2)")->check(CLI::Range(2, 16384));
  cmd->callback([] {
    const std::vector<lucent::OutputPath> outputs = {{output, "--output", {".hdr", ".exr"}}};
    lucent::check_outputs(outputs, {});
    const lucent::OutputLock lock(outputs);
    const lucent::ImageRGBA32F image = lucent::environment_map_to_image(map_named(kind, width));
    if (lucent::lowercase_extension(output) == ".exr") {
      lucent::write_exr(output, image);
    } else {
      lucent::write_hdr(output, image);
    }
    fmt::print("{}: {}x{} {} map\n", output, image.width, image.height, kind);
  });
}

void add_lights_command(CLI::App& app) {
  static std::string map_path;
  static int M = 8;
  CLI::App* cmd = app.add_subcommand("lights", "print the M directional lights of a map as a scene's \"lights\" array");
  cmd->add_option("map", map_path, "a .hdr or .exr file, or sky / gradient")->required();
  cmd->add_option("-M", M, "number of lights")->check(CLI::Range(1, 1024));
  cmd->callback([] {
    const auto lights = lucent::environment_to_directional_lights(map_named(map_path, 256), M);
    fmt::print("\"lights\": [\n");
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const auto& l = lights[i];
      fmt::print("  {{ \"direction\": [{:.5f}, {:.5f}, {:.5f}], \"radiance\": [{:.5g}, {:.5g}, {:.5g}] }}{}\n",
                 l.direction.x, l.direction.y, l.direction.z, l.radiance.r, l.radiance.g, l.radiance.b,
                 i + 1 < lights.size() ? "," : "");
    }
    fmt::print("]\n");
  });
}

void add_error_command(CLI::App& app) {
  static std::vector<std::string> maps = {"sky", "gradient"};
  static std::vector<int> Ms = {4, 8, 16, 32};
  static int width = 256, normal_count = 4096;
  CLI::App* cmd = app.add_subcommand("error", "irradiance error of M lights against the exact irradiance (markdown)");
  cmd->add_option("maps", maps, "files, or sky / gradient / constant (procedural, at --width)");
  cmd->add_option("-M", Ms, "numbers of lights")->check(CLI::Range(1, 1024));
  cmd->add_option("--width", width, "width of the procedural maps")->check(CLI::Range(2, 16384));
  cmd->add_option("--normals", normal_count, "normals spread over the sphere")->check(CLI::Range(1, 1 << 20));
  cmd->callback([] {
    const std::vector<glm::vec3> normals = lucent::sphere_directions(normal_count);
    fmt::print(
        "| map | M | median cut: max | RMS | stratified: max | RMS | variance cut: max | RMS | k-means: max | RMS |\n");
    fmt::print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const std::string& name : maps) {
      const EnvironmentMap map = map_named(name, width);
      const std::vector<glm::vec3> exact = lucent::environment_irradiance(map, normals);
      for (int M : Ms) {
        std::string row = fmt::format("| {} | {} |", name, M);
        for (EnvironmentSampling sampling : {EnvironmentSampling::MedianCut, EnvironmentSampling::Stratified,
                                             EnvironmentSampling::VarianceCut, EnvironmentSampling::KMeans}) {
          const auto lights = lucent::environment_to_directional_lights(map, M, sampling);
          const lucent::IrradianceError error = lucent::irradiance_error(normals, exact, lights);
          row += fmt::format(" {:.1f}% | {:.1f}% |", 100.0 * error.max_relative, 100.0 * error.rms_relative);
        }
        fmt::print("{}\n", row);
      }
    }
  });
}

}  // namespace

void add_envmap_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("envmap", "environment maps: make procedural ones, sample them into lights, measure");
  cmd->require_subcommand(1);
  add_make_command(*cmd);
  add_lights_command(*cmd);
  add_error_command(*cmd);
}

}  // namespace lucent::cli
