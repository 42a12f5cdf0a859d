// command_render.cpp: `lucent render [SCENE]`: headless render to PNG (and EXR) with per-step GPU timings.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "commands.h"
#include "option_checks.h"
#include "lucent/lucent.h"
#include "progress_bar.h"

namespace lucent::cli {
namespace {

struct RenderOptions {
  std::string scene_path;
  std::string png;
  std::string exr;
  std::optional<int> frames;
  std::optional<unsigned> seed;
  std::vector<std::string> sets;
  bool quiet = false;
  bool animate = false;
  int samples_per_frame = 1;
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

void print_timings(const std::vector<FrameTimings>& frames, const std::string& device, const std::string& method) {
  std::map<std::string, std::vector<double>> per_pass;
  std::vector<std::string> order;
  std::vector<double> step1, step2, step3, total, rate;
  for (const FrameTimings& t : frames) {
    for (const StepTiming& s : t.passes) {
      if (!per_pass.count(s.name)) order.push_back(s.name);
      per_pass[s.name].push_back(s.ms);
    }
    step1.push_back(t.light_gbuffer_ms), step2.push_back(t.radiosity_maps_ms), step3.push_back(t.combine_ms);
    total.push_back(t.total_ms);
    for (const StepTiming& s : t.passes)
      if ((s.name == "integrate" || s.name == "per_pixel") && s.ms > 0) rate.push_back(static_cast<double>(t.bssrdf_samples) / (s.ms * 1e-3));
  }
  fmt::print("GPU time per frame, median of {} frame(s), on {}:\n", frames.size(), device);
  fmt::print("  1. light G-buffer      {:10.3f} ms\n", median(step1));
  fmt::print("  2. radiosity maps      {:10.3f} ms\n", median(step2));
  fmt::print("  3. combine             {:10.3f} ms\n", median(step3));
  fmt::print("  total                  {:10.3f} ms\n", median(total));
  fmt::print("  passes:");
  for (const std::string& name : order) fmt::print(" {} {:.3f}", name, median(per_pass[name]));
  fmt::print(" (ms)\n  BSSRDF samples: {} per frame, {:.3g} per second in the integrate (or per_pixel) pass\n", frames.back().bssrdf_samples,
             median(rate));
  const FrameTimings& last = frames.back();
  if (method == "radiosity-maps")
    fmt::print("  translucent pixels: {}, seen by the maps: {:.2f}%{}\n", last.translucent_pixels, 100.0 * last.map_coverage,
               last.map_coverage < 0.999 ? " (view=coverage shows the rest in magenta; raise method.K)" : "");
  else
    fmt::print("  translucent pixels: {}\n", last.translucent_pixels);
}

std::string default_png_path(const std::string& scene_path) {
  std::string stem = scene_path.empty() ? "default" : std::filesystem::path(scene_path).stem().string();
  return (std::filesystem::path("out") / (stem + ".png")).string();
}

void warn_if_black(const ImageRGBA32F& image) {
  float peak = 0.0f;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4)
    peak = std::max({peak, image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]});
  if (!(peak > 0.0f)) fmt::print(stderr, "lucent: warning: the image is black (no light reaches the camera)\n");
}

// `--animate`: frame f shows time f / fps, accumulated over `samples_per_frame` renders, written as
// <stem>_0000.png, ...; with ffmpeg on the PATH also <stem>.mp4.
void run_animation(const RenderOptions& o, const Scene& scene, const std::string& png) {
  auto context = create_headless_context();
  Renderer renderer(scene);
  int width = scene.render.width, height = scene.render.height, frames = scene.render.frames;
  OffscreenFramebuffer target(width, height);
  std::filesystem::path base = std::filesystem::path(png).replace_extension("");
  ProgressBar progress("animating", o.quiet ? 1 : frames);
  std::vector<FrameTimings> timings;
  for (int f = 0; f < frames; ++f) {
    renderer.set_time(f / static_cast<double>(scene.render.fps));
    for (int s = 0; s < o.samples_per_frame; ++s) {
      renderer.render(scene.camera, {target.id(), width, height});
      timings.push_back(renderer.timings());
    }
    write_png(fmt::format("{}_{:04d}.png", base.string(), f), renderer.read_display());
    progress.update(f + 1);
  }
  progress.finish();
  std::string pattern = base.string() + "_%04d.png", mp4 = base.string() + ".mp4";
  bool have_ffmpeg = std::system("command -v ffmpeg > /dev/null 2>&1") == 0;
  if (have_ffmpeg) {
    // ffmpeg writes a temporary file that replaces the MP4 only when complete, as lucent's own outputs do.
    std::filesystem::path partial = base.parent_path() / ("." + base.filename().string() + ".lucent-tmp.mp4");
    std::string command = fmt::format("ffmpeg -loglevel error -y -framerate {} -i '{}' -pix_fmt yuv420p '{}'",
                                      scene.render.fps, pattern, partial.string());
    std::error_code ec;
    if (std::system(command.c_str()) != 0) {
      std::filesystem::remove(partial, ec);
      throw Error(fmt::format("{}: ffmpeg failed: {}", mp4, command));
    }
    std::filesystem::rename(partial, mp4, ec);
    if (ec) throw Error(fmt::format("{}: cannot write: {}", mp4, ec.message()));
  }
  if (!o.quiet) {
    fmt::print("{}: {} frames at {} fps, {} sample(s) each -> {}{}\n", scene.source, frames, scene.render.fps,
               o.samples_per_frame, pattern, have_ffmpeg ? " and " + mp4 : " (no ffmpeg: no MP4)");
    print_timings(timings, renderer.device(), scene.method);
  }
}

void run(const RenderOptions& o) {
  std::vector<std::string> overrides = o.sets;
  if (o.frames) overrides.push_back(fmt::format("render.frames={}", *o.frames));
  if (o.seed) overrides.push_back(fmt::format("render.seed={}", *o.seed));
  Scene scene = o.scene_path.empty() ? default_scene(overrides) : load_scene(o.scene_path, overrides);
  std::string png = o.png.empty() ? default_png_path(o.scene_path) : o.png;
  // Outputs are checked before the first frame: never an input, a known format, a directory that takes files.
  std::vector<OutputPath> outputs = {{png, "--output", {".png"}}, {o.exr, "--exr", {".exr"}}};
  if (o.animate) {
    std::filesystem::path base = std::filesystem::path(png).replace_extension("");
    if (!o.exr.empty()) throw Error("--exr: not written with --animate (each frame is a PNG)");
    outputs.push_back({fmt::format("{}_{:04d}.png", base.string(), 0), "--output (first frame)", {".png"}});
    outputs.push_back({base.string() + ".mp4", "--output (video)", {".mp4"}});
  }
  check_outputs(outputs, scene_input_files(scene));
  if (o.animate) return run_animation(o, scene, png);
  auto context = create_headless_context();
  Renderer renderer(scene);
  int width = scene.render.width, height = scene.render.height, frames = scene.render.frames;
  OffscreenFramebuffer target(width, height);
  ProgressBar progress("rendering", o.quiet ? 1 : frames);
  std::vector<FrameTimings> timings;
  for (int f = 0; f < frames; ++f) {
    renderer.render(scene.camera, {target.id(), width, height});
    timings.push_back(renderer.timings());
    progress.update(f + 1);
  }
  progress.finish();

  ImageRGBA32F radiance = renderer.read_radiance();
  warn_if_black(radiance);
  write_png(png, renderer.read_display());
  if (!o.exr.empty()) write_exr(o.exr, radiance);
  if (!o.quiet) {
    fmt::print("{}: {}x{}, {} frame(s) accumulated -> {}{}\n", scene.source, width, height,
               renderer.accumulated_frames(), png, o.exr.empty() ? "" : " and " + o.exr);
    print_timings(timings, renderer.device(), scene.method);
  }
}

std::string render_help_footer() {
  std::string text = "\nScene parameters (scene file keys; override any with --set path=value):\n";
  for (const ParamSection& section : scene_param_sections())
    text += fmt::format("\n [{}]\n{}", section.name, describe(section, 3));
  return text;
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "render a scene headless to PNG (and EXR)");
  cmd->add_option("scene", options->scene_path, "scene file (JSON); the built-in default scene when omitted");
  cmd->add_option("-o,--output", options->png, "tone-mapped PNG (default: out/<scene>.png)");
  cmd->add_option("--exr", options->exr, "also write linear radiance as EXR");
  cmd->add_option("--frames", options->frames, "frames to accumulate (render.frames)")->check(whole_number_in(1, 1e6));
  cmd->add_option("--seed", options->seed, "random seed (render.seed)")->check(whole_number_in(0, 4294967295.0));
  cmd->add_option("--set", options->sets, "override a scene value, e.g. --set method.K=8 --set render.width=320");
  cmd->add_flag("-q,--quiet", options->quiet, "print nothing but errors");
  add_no_cache_flag(cmd);
  cmd->add_flag("--animate", options->animate,
                "render --frames animation frames (time f / render.fps) to <output>_NNNN.png, and an MP4 with ffmpeg");
  cmd->add_option("--samples-per-frame", options->samples_per_frame, "--animate: frames accumulated per animation frame")
      ->check(CLI::Range(1, 100000));
  cmd->footer(render_help_footer());
  cmd->callback([options] { run(*options); });
}

}  // namespace lucent::cli
