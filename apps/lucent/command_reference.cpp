// command_reference.cpp: `lucent reference SCENE`: CPU ground truth (volumetric path tracing, or Monte Carlo
// integration of the BSSRDF model), with a progress bar, the time left, a standard-error image, and resuming.
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "params/param_json.h"
#include "progress_bar.h"
#include "reference/reference_renderer.h"

namespace lucent::cli {
namespace {

struct ReferenceOptions {
  std::string scene_path;
  std::string output = "out/reference.exr";
  std::string integrator = "volpath";
  reference::ReferenceSettings settings;
  std::vector<std::string> sets;
  bool resume = false;
  bool quiet = false;
};

reference::ReferenceImage load_previous(const std::string& exr) {
  std::string meta_path = reference::reference_sidecar(exr, ".json");
  std::ifstream meta(meta_path);
  if (!meta) throw Error(fmt::format("{}: cannot resume: no such file (written next to the reference)", meta_path));
  nlohmann::json j = try_parse_json(meta, meta_path);
  if (j.is_discarded() || !j.contains("samples_per_pixel"))
    throw Error(fmt::format("{}: cannot resume: malformed metadata", meta_path));
  reference::ReferenceImage previous;
  previous.mean = read_exr(exr);
  previous.standard_error = read_exr(reference::reference_sidecar(exr, ".stderr.exr"));
  previous.samples_per_pixel = j["samples_per_pixel"].get<int>();
  previous.seconds = j.value("seconds", 0.0);
  return previous;
}

void run(ReferenceOptions o) {
  if (o.integrator != "volpath" && o.integrator != "bssrdf")
    throw Error(fmt::format("--integrator: '{}' is not one of volpath, bssrdf", o.integrator));
  o.settings.integrator = o.integrator == "volpath" ? reference::Integrator::Volpath : reference::Integrator::Bssrdf;
  Scene scene = load_scene(o.scene_path, o.sets);
  std::optional<reference::ReferenceImage> previous;
  if (o.resume) previous = load_previous(o.output);
  ProgressBar progress(fmt::format("{} {} spp", o.integrator, o.settings.samples_per_pixel), o.quiet ? 1 : 1000);
  o.settings.progress = [&](double done) { progress.update(static_cast<int>(done * 1000.0)); };
  reference::ReferenceImage image = reference::render_reference(scene, o.settings, previous ? &*previous : nullptr);
  progress.finish();
  if (previous) image.seconds += previous->seconds;
  auto parent = std::filesystem::path(o.output).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  write_exr(o.output, image.mean);
  write_exr(reference::reference_sidecar(o.output, ".stderr.exr"), image.standard_error);
  double paths = static_cast<double>(scene.render.width) * scene.render.height * image.samples_per_pixel;
  nlohmann::json meta = {{"scene", o.scene_path},
                         {"integrator", o.integrator},
                         {"samples_per_pixel", image.samples_per_pixel},
                         {"seed", o.settings.seed},
                         {"width", scene.render.width},
                         {"height", scene.render.height},
                         {"seconds", image.seconds},
                         {"camera_paths_per_second", paths / image.seconds},
                         {"overrides", o.sets}};
  std::ofstream(reference::reference_sidecar(o.output, ".json")) << meta.dump(2) << "\n";
  if (!o.quiet)
    fmt::print("{}: {} {}x{}, {} spp in {:.1f} s ({:.3g} camera paths/s) -> {} (+ .stderr.exr, .json)\n",
               o.scene_path, o.integrator, scene.render.width, scene.render.height, image.samples_per_pixel,
               image.seconds, paths / image.seconds, o.output);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand("reference", "render CPU ground truth: volumetric path tracing or the BSSRDF model");
  cmd->add_option("scene", o->scene_path, "scene file (JSON)")->required();
  cmd->add_option("--integrator", o->integrator, "volpath (the physics) | bssrdf (the model)")->capture_default_str();
  cmd->add_option("--spp", o->settings.samples_per_pixel, "samples per pixel to add")->capture_default_str();
  cmd->add_option("-o,--output", o->output, "mean radiance EXR; also writes <stem>.stderr.exr and <stem>.json")
      ->capture_default_str();
  cmd->add_option("--threads", o->settings.threads, "threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--seed", o->settings.seed, "random seed")->capture_default_str();
  cmd->add_flag("--jitter", o->settings.jitter, "jitter rays inside pixels (default: pixel centres, as rasterized)");
  cmd->add_flag("--resume", o->resume, "add samples to the existing output (same scene and seed)");
  cmd->add_option("--set", o->sets, "override a scene value, e.g. --set render.width=160");
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o] { run(*o); });
}

}  // namespace lucent::cli
