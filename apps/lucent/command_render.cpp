// command_render.cpp: `lucent render [SCENE]`: headless render to PNG (and EXR) with per-step GPU timings.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <span>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "commands.h"
#include "io/interruption.h"
#include "option_checks.h"
#include "lucent/lucent.h"
#include "progress_bar.h"
#include "step_progress.h"
#include "stats/frame_summary.h"

namespace lucent::cli {
namespace {

struct RenderOptions {
  std::string scene_path;
  std::string output;  // -o: PNG (tone-mapped) or EXR (linear radiance), by its extension
  std::string exr;     // --exr: linear radiance besides the -o file
  std::string timings_json;
  std::optional<int> frames;
  std::optional<unsigned> seed;
  std::vector<std::string> sets;
  bool quiet = false;
  bool animate = false;
  bool restart_every_frame = false;
  bool denoise = false;
  int samples_per_frame = 1;
};

void print_timings(const std::vector<FrameTimings>& frames, const std::string& device) {
  if (frames.empty()) return;
  stats::FrameSummary summary = stats::summarize(frames);
  fmt::print("{}", stats::format_summary(summary, device));
  double coverage = frames.back().stat("coverage", 1.0);
  if (coverage < 0.999)
    fmt::print("  {:.2f}% of the translucent pixels have no data from the method (see its debug views)\n",
               100.0 * (1.0 - coverage));
}

void write_timings_json(const std::string& path, const std::vector<FrameTimings>& frames) {
  if (path.empty()) return;
  std::string text = stats::timings_json(frames);
  write_file(path, text);
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

// The PNG of animation frame f: <base>_0000.png, ...
std::string frame_path(const std::filesystem::path& base, int f) { return fmt::format("{}_{:04d}.png", base.string(), f); }

// `--animate`: frame f shows time f / fps, accumulated over `samples_per_frame` renders, written as
// <stem>_0000.png, ...; with ffmpeg on the PATH also <stem>.mp4.
void run_animation(const RenderOptions& o, const Scene& scene, const std::string& png) {
  auto context = create_headless_context();
  Renderer renderer(scene, o.quiet ? RenderProgress{} : RenderProgress(StepProgress()));
  int width = scene.render.width, height = scene.render.height, frames = scene.render.frames;
  OffscreenFramebuffer target(width, height);
  std::filesystem::path base = std::filesystem::path(png).replace_extension("");
  ProgressBar progress("animating", o.quiet ? 1 : frames, "frames");
  std::vector<FrameTimings> timings;
  for (int f = 0; f < frames; ++f) {
    renderer.set_time(f / static_cast<double>(scene.render.fps));
    for (int s = 0; s < o.samples_per_frame; ++s) {
      renderer.render(scene.camera, {target.id(), width, height});
      for (FrameTimings& t : renderer.finished_frames(false)) timings.push_back(std::move(t));
    }
    write_png(frame_path(base, f), renderer.read_display());
    progress.update(f + 1);
  }
  progress.finish();
  for (FrameTimings& t : renderer.finished_frames(true)) timings.push_back(std::move(t));
  write_timings_json(o.timings_json, timings);
  std::string pattern = base.string() + "_%04d.png", mp4 = base.string() + ".mp4";
  bool have_ffmpeg = std::system("command -v ffmpeg > /dev/null 2>&1") == 0;
  if (have_ffmpeg) {
    // ffmpeg writes a temporary file that replaces the MP4 only when complete, as lucent's own outputs do. It reads
    // this animation's frames only (-frames:v), not those an earlier, longer one left after them, and never its
    // standard input (-nostdin), which belongs to whoever started lucent: a pipe's lines or a terminal whose
    // background jobs ffmpeg would stop.
    std::filesystem::path partial = base.parent_path() / ("." + base.filename().string() + ".lucent-tmp.mp4");
    std::string command =
        fmt::format("ffmpeg -nostdin -loglevel error -y -framerate {} -i '{}' -frames:v {} -pix_fmt yuv420p '{}'",
                    scene.render.fps, pattern, frames, partial.string());
    std::error_code ec;
    const RemoveOnSignal removal(partial.string());  // a signal that ends lucent meanwhile leaves no partial video
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
    print_timings(timings, renderer.device());
  }
}

void run(const RenderOptions& o) {
  std::vector<std::string> overrides = o.sets;
  if (o.denoise) overrides.insert(overrides.begin(), "denoise.enabled=true");  // a --set may still turn it off
  if (o.frames) overrides.push_back(fmt::format("render.frames={}", *o.frames));
  if (o.seed) overrides.push_back(fmt::format("render.seed={}", *o.seed));
  Scene scene = o.scene_path.empty() ? default_scene(overrides) : load_scene(o.scene_path, overrides);
  const std::string output = o.output.empty() ? default_png_path(o.scene_path) : o.output;
  // -o's extension picks the format: .png tone-mapped, .exr linear radiance (--exr adds an EXR beside a PNG).
  const bool output_is_exr = lowercase_extension(output) == ".exr";
  if (o.animate && output_is_exr)
    throw Error(fmt::format("--output {}: --animate writes PNG frames; give a .png", output));
  const std::string png = output_is_exr ? "" : output;
  // Outputs are checked before the first frame: never an input, a known format, a directory that takes files.
  std::vector<OutputPath> outputs = {{output, "--output", {".png", ".exr"}},
                                     {o.exr, "--exr", {".exr"}},
                                     {o.timings_json, "--timings-json", {".json"}}};
  if (o.animate) {
    std::filesystem::path base = std::filesystem::path(png).replace_extension("");
    if (!o.exr.empty()) throw Error("--exr: not written with --animate (each frame is a PNG)");
    // Every frame and the video: a scene's texture named like frame 1 must not be replaced by it.
    for (int f = 0; f < scene.render.frames; ++f)
      outputs.push_back({frame_path(base, f), fmt::format("--output (frame {})", f), {".png"}});
    outputs.push_back({base.string() + ".mp4", "--output (video)", {".mp4"}});
  }
  check_outputs(outputs, scene_input_files(scene));
  // Held until the last file is written. An animation's frames are named after its --output and locked with it.
  std::vector<OutputPath> locked = {outputs[0], outputs[1], outputs[2]};
  if (o.animate) locked.push_back(outputs.back());
  const OutputLock lock(locked);
  if (o.animate) return run_animation(o, scene, png);
  auto context = create_headless_context();
  Renderer renderer(scene, o.quiet ? RenderProgress{} : RenderProgress(StepProgress()));
  int width = scene.render.width, height = scene.render.height, frames = scene.render.frames;
  OffscreenFramebuffer target(width, height);
  ProgressBar progress("rendering", o.quiet ? 1 : frames, "frames");
  std::vector<FrameTimings> timings;
  for (int f = 0; f < frames; ++f) {
    if (o.restart_every_frame) renderer.restart();
    renderer.render(scene.camera, {target.id(), width, height});
    for (FrameTimings& t : renderer.finished_frames(false)) timings.push_back(std::move(t));
    progress.update(f + 1);
  }
  progress.finish();
  for (FrameTimings& t : renderer.finished_frames(true)) timings.push_back(std::move(t));

  ImageRGBA32F radiance = renderer.read_radiance();
  warn_if_black(radiance);
  if (output_is_exr) write_exr(output, radiance);
  else write_png(output, renderer.read_display());
  if (!o.exr.empty()) write_exr(o.exr, radiance);
  write_timings_json(o.timings_json, timings);
  if (!o.quiet) {
    fmt::print("{}: {}x{}, {} frame(s) accumulated -> {}{}\n", scene.source, width, height,
               renderer.accumulated_frames(), output, o.exr.empty() ? "" : " and " + o.exr);
    print_timings(timings, renderer.device());
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
  cmd->add_option("-o,--output", options->output,
                  "image to write, its format from the extension: .png tone-mapped (ACES, sRGB), .exr linear radiance "
                  "(default: out/<scene>.png)");
  cmd->add_option("--exr", options->exr, "also write linear radiance as EXR (beside a PNG --output)");
  cmd->add_option("--timings-json", options->timings_json,
                  "write every frame's GPU pass times and the method's statistics as JSON");
  cmd->add_option("--frames", options->frames, "frames to accumulate (render.frames)")->check(whole_number_in(1, 1e6));
  cmd->add_option("--seed", options->seed, "random seed (render.seed)")->check(whole_number_in(0, 4294967295.0));
  cmd->add_option("--set", options->sets, "override a scene value, e.g. --set method.K=8 --set render.width=320");
  cmd->add_flag("-q,--quiet", options->quiet, "print nothing but errors");
  cmd->add_flag("--denoise", options->denoise,
                "filter the method's image (denoise.enabled): history reprojected across camera moves and an "
                "edge-stopping wavelet filter; biased, for a few paths per pixel");
  add_no_cache_flag(cmd);
  cmd->add_flag("--animate", options->animate,
                "render --frames animation frames (time f / render.fps) to <output>_NNNN.png, and an MP4 with ffmpeg");
  cmd->add_flag("--restart-every-frame", options->restart_every_frame,
                "recompute everything the method caches every frame, as when the scene changes (for timings; the "
                "image is then the last frame alone)")
      ->excludes("--animate");
  cmd->add_option("--samples-per-frame", options->samples_per_frame, "--animate: frames accumulated per animation frame")
      ->check(CLI::Range(1, 100000));
  cmd->footer(render_help_footer());
  cmd->callback([options] { run(*options); });
}

}  // namespace lucent::cli
