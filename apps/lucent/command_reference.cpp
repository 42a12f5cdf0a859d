// command_reference.cpp: `lucent reference SCENE`: CPU ground truth (volumetric path tracing, or Monte Carlo
// integration of the BSSRDF model), with a progress bar, the time left, a standard-error image, and resuming;
// `lucent reference merge A.exr B.exr ... -o ref.exr`: batches rendered with distinct seeds, combined exactly.
#include <algorithm>
#include <csignal>
#include <cstring>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "interrupted.h"
#include "io/interruption.h"
#include "option_checks.h"
#include "lucent/error.h"
#include "lucent/output_file.h"
#include "lucent/scene.h"
#include "params/argument_ranges.h"
#include "progress_bar.h"
#include "sample_progress.h"
#include "reference/reference_files.h"
#include "reference/reference_merge.h"
#include "render/gpu_reference.h"
#include "lucent/context.h"

namespace lucent::cli {
namespace {

// A shell without job control starts a background job (`lucent reference ... &` in a script) with SIGINT ignored,
// and install_interruption_handlers() leaves an ignored signal ignored: `kill -INT` then did nothing and the
// reference ran on. A reference stopped by SIGINT saves its samples and says how to resume, so it takes SIGINT
// whatever it inherited (SIGHUP stays ignored under nohup).
void take_sigint_even_if_ignored() {
  struct sigaction old {};
  if (::sigaction(SIGINT, nullptr, &old) != 0 || old.sa_handler != SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  install_interruption_handlers();
}

struct ReferenceOptions {
  std::string scene_path;
  std::string output = "out/reference.exr";
  std::string integrator = "volpath";
  reference::ReferenceSettings settings;
  std::vector<std::string> sets;
  std::string sphere_jumps = "on";
  std::string device = "cpu";
  bool resume = false;
  bool quiet = false;
};

// Samples are added only to a reference of the same image: the same integrator, seed, pixel sampling and size (the
// metadata of older versions has no jitter: taken as false). The total stays within an int.
void check_resumable(const nlohmann::json& meta, const ReferenceOptions& o, const Scene& scene, const std::string& path) {
  auto differs = [&](const char* key, const nlohmann::json& now) { return meta.contains(key) && meta[key] != now; };
  const std::pair<const char*, nlohmann::json> keys[] = {{"integrator", o.integrator},
                                                         {"seed", o.settings.seed},
                                                         {"jitter", o.settings.jitter},
                                                         {"max_scatter", o.settings.max_scatter},
                                                         {"width", scene.render.width},
                                                         {"height", scene.render.height},
                                                         {"scene_hash", reference::scene_content_hash(scene)}};
  // A GPU batch's standard error is the spread of its batches, a CPU run's the spread of its samples: resumed, the
  // file would be labelled with one device and hold both. A merge keeps each input's own.
  if (meta.contains("device") && meta["device"] == "gpu")
    throw Error(fmt::format("{}: cannot resume: the reference was rendered on the gpu; render the other samples as a "
                            "batch of their own (another --seed) and combine both with lucent reference merge",
                            path));
  const int version = reference::reference_version(meta);
  if (version != reference::kReferenceVersion)
    throw Error(fmt::format("{}: cannot resume: the reference was rendered by version {} of the references' "
                            "estimators, this lucent renders version {}; its samples estimate another image: render "
                            "it anew",
                            path, version, reference::kReferenceVersion));
  // A bssrdf reference integrates the objects' models, which a scene without "model" keys leaves to the default:
  // one rendered before its models were recorded cannot be told to be the same image.
  const std::string models = reference::scene_models(scene);
  if (o.integrator == "bssrdf" && (!meta.contains("models") || meta["models"] != models))
    throw Error(fmt::format("{}: cannot resume: the reference integrates the models {}, this run {}; render it anew",
                            path, meta.contains("models") ? meta["models"].dump() : "(not recorded)", models));
  for (const auto& [key, now] : keys)
    if (differs(key, now))
      throw Error(fmt::format("{}: cannot resume: the reference has {} {}, this run {}", path, key, meta[key].dump(),
                              now.dump()));
  const long long total = static_cast<long long>(meta["samples_per_pixel"].get<int>()) + o.settings.samples_per_pixel;
  if (total > std::numeric_limits<int>::max())
    throw Error(fmt::format("{}: cannot resume: {} + {} samples per pixel exceed {}", path,
                            meta["samples_per_pixel"].get<int>(), o.settings.samples_per_pixel,
                            std::numeric_limits<int>::max()));
}

void run(ReferenceOptions o) {
  if (o.integrator != "volpath" && o.integrator != "bssrdf")
    throw Error(fmt::format("--integrator: '{}' is not one of volpath, bssrdf", o.integrator));
  o.settings.integrator = o.integrator == "volpath" ? reference::Integrator::Volpath : reference::Integrator::Bssrdf;
  if (o.settings.max_scatter > 0 && o.settings.integrator != reference::Integrator::Volpath)
    throw Error("--max-scatter: only the volpath integrator counts scattering events");
  if (o.sphere_jumps != "on" && o.sphere_jumps != "off")
    throw Error(fmt::format("--sphere-jumps: '{}' is not one of on, off", o.sphere_jumps));
  o.settings.sphere_jumps = o.sphere_jumps == "on";
  if (o.device != "cpu" && o.device != "gpu")
    throw Error(fmt::format("--device: '{}' is not one of cpu, gpu", o.device));
  if (o.device == "gpu" && o.settings.integrator != reference::Integrator::Volpath)
    throw Error("--device gpu: only the volpath integrator runs on the GPU; render bssrdf references on the cpu");
  if (o.device == "gpu" && o.resume)
    throw Error("--resume: --device gpu renders a new batch; render batches with distinct --seed and combine them "
                "with lucent reference merge");
  if (o.device == "gpu" && o.settings.jitter) throw Error("--jitter: --device gpu renders through pixel centres only");
  if (o.output.empty()) throw Error("--output: empty path; give the reference's EXR, e.g. out/ref.exr");
  Scene scene = load_scene(o.scene_path, o.sets);
  // The three files are checked before the first sample: a reference can take hours.
  const reference::ReferenceFiles files = reference::reference_files(o.output);
  const std::vector<OutputPath> outputs = {{files.mean, "--output", {".exr"}},
                                           {files.standard_error, "--output (standard error)", {".exr"}},
                                           {files.metadata, "--output (metadata)", {".json"}}};
  check_outputs(outputs, scene_input_files(scene));
  // Held from before the previous samples are read (--resume) until the new set is renamed into place: a second
  // lucent writing this reference fails at once instead of mixing the sets or counting the same samples twice.
  const OutputLock lock(outputs);
  const std::string scene_hash = reference::scene_content_hash(scene);
  std::optional<reference::StoredReference> previous;
  if (o.resume) {
    previous = reference::load_reference(files);
    check_resumable(previous->metadata, o, scene, files.metadata);
  }
  // The bar shows samples per pixel in completed passes and a time left from their measured seconds per sample.
  ProgressBar progress(o.integrator, o.quiet ? 1 : 1000);
  SampleEta eta(previous ? previous->image.samples_per_pixel : 0, o.settings.samples_per_pixel);
  o.settings.progress = [&](double done) {
    eta.update(done);
    progress.draw(done, eta.text(progress.elapsed()));
  };
  o.settings.pass_done = [&](int samples_done) { eta.pass_completed(samples_done, progress.elapsed()); };
  // SIGINT or SIGTERM stops the render at its next chunk of rows; the completed passes are saved, then the command
  // ends with a line saying how many samples it saved.
  take_sigint_even_if_ignored();
  DeferredInterruption interruption;
  o.settings.stop_requested = [&] { return interruption.received() != 0; };
  std::string gpu;
  std::unique_ptr<GLContext> context;
  if (o.device == "gpu") context = create_headless_context();
  reference::ReferenceImage image = o.device == "gpu"
                                        ? render::render_reference_on_gpu(scene, o.settings, &gpu)
                                        : reference::render_reference(scene, o.settings, previous ? &previous->image : nullptr);
  progress.finish();
  const int asked = o.settings.samples_per_pixel;
  const int added = image.samples_per_pixel - (previous ? previous->image.samples_per_pixel : 0);
  const int signal = added < asked ? interruption.take() : 0;
  const std::string why =
      fmt::format("interrupted by SIG{}", signal && sigabbrev_np(signal) ? sigabbrev_np(signal) : "?");
  if (signal && added == 0)
    throw Interrupted(signal, fmt::format("{} before its first pass of samples ended: {} {}", why, files.mean,
                                          previous ? "is unchanged" : "was not written"));
  if (previous) image.seconds += previous->image.seconds;
  double paths = static_cast<double>(scene.render.width) * scene.render.height * image.samples_per_pixel;
  nlohmann::json metadata = {{"scene", o.scene_path},
                             {"scene_hash", scene_hash},
                             {"reference_version", reference::kReferenceVersion},
                             {"integrator", o.integrator},
                             {"models", reference::scene_models(scene)},
                             {"seed", o.settings.seed},
                             {"jitter", o.settings.jitter},
                             {"max_scatter", o.settings.max_scatter},
                             {"sphere_jumps", o.settings.sphere_jumps},
                             {"device", o.device},
                             {"time_seconds", o.settings.time_seconds},
                             {"width", scene.render.width},
                             {"height", scene.render.height},
                             {"camera_paths_per_second", paths / image.seconds},
                             {"steps_per_path", image.steps_per_path},
                             {"steps_per_path_standard_error", image.steps_per_path_standard_error},
                             {"overrides", o.sets}};
  // A merged reference resumed: its samples are those of its seeds and now this one's too (what a later merge
  // checks), and it keeps the list of its inputs.
  if (previous && previous->metadata.contains("seeds")) {
    std::vector<std::uint64_t> seeds = reference::reference_seeds(previous->metadata, files.metadata);
    if (std::find(seeds.begin(), seeds.end(), o.settings.seed) == seeds.end()) seeds.push_back(o.settings.seed);
    metadata["seeds"] = seeds;
    if (previous->metadata.contains("inputs")) metadata["inputs"] = previous->metadata["inputs"];
  }
  if (!gpu.empty()) metadata["gpu"] = gpu;
  reference::save_reference(files, image, std::move(metadata));
  if (signal && o.device == "gpu")  // a GPU batch does not resume: another seed's batch merges with it
    throw Interrupted(signal, fmt::format("{}: saved {} of the {} samples per pixel asked in {}; to add the other {}, "
                                          "render them with a different --seed (--device gpu --spp {} --seed {} -o "
                                          "<other>.exr) and combine both with lucent reference merge",
                                          why, added, asked, files.mean, asked - added, asked - added,
                                          o.settings.seed + 1));
  if (signal)
    throw Interrupted(signal, fmt::format("{}: saved {} of the {} samples per pixel asked ({} in all) in {}; to add "
                                          "the other {}, run the same command with --resume --spp {}",
                                          why, added, asked, image.samples_per_pixel, files.mean, asked - added,
                                          asked - added));
  if (!o.quiet)
    fmt::print("{}: {} {}x{}, {} spp in {:.1f} s ({:.3g} camera paths/s) -> {} (+ {}, {})\n", o.scene_path,
               o.integrator, scene.render.width, scene.render.height, image.samples_per_pixel, image.seconds,
               paths / image.seconds, files.mean, files.standard_error, files.metadata);
}

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string output;
  bool quiet = false;
};

void merge(const MergeOptions& o) {
  if (o.inputs.size() < 2) throw Error("reference merge: give two or more references to merge");
  if (o.output.empty()) throw Error("--output: empty path; give the merged reference's EXR, e.g. out/ref.exr");
  // No output may be an input or one of its companions: the inputs stay as they are.
  std::vector<std::string> inputs;
  for (const std::string& input : o.inputs) {
    const reference::ReferenceFiles f = reference::reference_files(input);
    inputs.insert(inputs.end(), {f.mean, f.standard_error, f.metadata});
  }
  const reference::ReferenceFiles files = reference::reference_files(o.output);
  const std::vector<OutputPath> outputs = {{files.mean, "--output", {".exr"}},
                                           {files.standard_error, "--output (standard error)", {".exr"}},
                                           {files.metadata, "--output (metadata)", {".json"}}};
  check_outputs(outputs, inputs);
  const OutputLock lock(outputs);
  reference::StoredReference merged = reference::merge_references(o.inputs);
  reference::save_reference(files, merged.image, merged.metadata);
  if (!o.quiet)
    fmt::print("{} references, {} spp, {:.1f} s of rendering -> {} (+ {}, {})\n", o.inputs.size(),
               merged.image.samples_per_pixel, merged.image.seconds, files.mean, files.standard_error, files.metadata);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand("reference", "render CPU ground truth: volumetric path tracing or the BSSRDF model");
  cmd->require_subcommand(0, 1);
  auto m = std::make_shared<MergeOptions>();
  CLI::App* merge_cmd = cmd->add_subcommand(
      "merge",
      "combine references rendered with distinct seeds (the same scene and settings, e.g. on several machines) into "
      "the reference of all their samples");
  merge_cmd->add_option("inputs", m->inputs, "the batches' mean EXRs (each with its .stderr.exr and .meta.json)")
      ->required();
  merge_cmd->add_option("-o,--output", m->output,
                        "merged mean EXR; also writes <stem>.stderr.exr and <stem>.meta.json (never an input)")
      ->required();
  merge_cmd->add_flag("-q,--quiet", m->quiet, "print nothing but errors");
  merge_cmd->callback([m] { merge(*m); });
  // The scene is required unless `merge` is given (checked in the callback: a required option would refuse it).
  cmd->add_option("scene", o->scene_path, "scene file (JSON); or `merge`, see lucent reference merge --help");
  cmd->add_option("--integrator", o->integrator, "volpath (the physics) | bssrdf (the model)")->capture_default_str();
  cmd->add_option("--spp", o->settings.samples_per_pixel, "samples per pixel to add")
      ->check(number_in(argument_ranges::kSamplesPerPixel))
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "mean radiance EXR; also writes <stem>.stderr.exr and <stem>.meta.json")
      ->capture_default_str();
  cmd->add_option("--threads", o->settings.threads, "threads (0 = all cores)")
      ->check(number_in(argument_ranges::kThreads))
      ->capture_default_str();
  cmd->add_option("--seed", o->settings.seed, "random seed (batches to be merged need distinct seeds)")->check(number_in(argument_ranges::kReferenceSeed))->capture_default_str();
  cmd->add_flag("--jitter", o->settings.jitter, "jitter rays inside pixels (default: pixel centres, as rasterized)");
  cmd->add_option("--max-scatter", o->settings.max_scatter,
                  "volpath: end paths after this many scattering events (1: single scattering; 0: no limit)")
      ->check(number_in(argument_ranges::kMaxScatter))
      ->capture_default_str();
  cmd->add_option("--sphere-jumps", o->sphere_jumps,
                  "volpath: jump across spheres inside homogeneous media instead of stepping through every collision "
                  "(on | off; the same image either way)")
      ->capture_default_str();
  cmd->add_option("--device", o->device,
                  "volpath: cpu (Embree) or gpu (the random-walk method on the GPU: the same image, its standard "
                  "error from 16 batches; merges with CPU batches)")
      ->capture_default_str();
  cmd->add_flag("--resume", o->resume, "add samples to the existing output (same scene and seed)");
  cmd->add_option("--set", o->sets, "override a scene value, e.g. --set render.width=160");
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, merge_cmd] {
    if (merge_cmd->parsed()) return;
    if (o->scene_path.empty()) throw CLI::RequiredError("scene");
    run(*o);
  });
}

}  // namespace lucent::cli
