// command_bench.cpp: `lucent bench CONFIG`: a matrix of scenes x method variants, measured against the CPU
// references. Per variant: per-pass GPU times (median and range over the frames after a warm-up frame), the
// method's statistics, GPU memory, coverage of the visible surface, and the error against the
// converged references (and, on request, the error of the BSSRDF reference at equal time). Writes results.json,
// results.md, results.tsv, side-by-side images and, where the config names a gnuplot script, plots.
// References are cached under the output folder, keyed by the scene and the overrides that change the image.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "bench_config.h"
#include "commands.h"
#include "denoise/denoise_params.h"
#include "image/image_metrics.h"
#include "io/input_file.h"
#include "lucent/lucent.h"
#include "params/param_json.h"
#include "progress_bar.h"
#include "reference/image_region.h"
#include "reference/reference_cache.h"
#include "stats/frame_summary.h"

namespace lucent::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

std::vector<std::string> strings(const json& j, const char* key) {
  std::vector<std::string> out;
  if (j.contains(key))
    for (const auto& s : j.at(key)) out.push_back(s.get<std::string>());
  return out;
}

// A variant's overrides: the configuration's, then its run's, then its own ("set" lists of "key=value"), then those
// of the command line (`lucent bench --set`), which win.
std::vector<std::string> variant_overrides(const json& config, const json& run, const json& variant,
                                           const std::vector<std::string>& command_line) {
  std::vector<std::string> sets = strings(config, "set");
  for (const auto& s : strings(run, "set")) sets.push_back(s);
  for (const auto& s : strings(variant, "set")) sets.push_back(s);
  for (const auto& s : command_line) sets.push_back(s);
  return sets;
}

// A run's "regions" (reference/image_region.h): parts of the image measured on their own.
std::vector<reference::ImageRegion> run_regions(const json& run) {
  std::vector<reference::ImageRegion> regions;
  for (const json& r : run.value("regions", json::array())) {
    reference::ImageRegion region;
    region.name = r.at("name").get<std::string>();
    region.object = r.at("object").get<std::string>();
    if (r.contains("center"))
      for (int c = 0; c < 3; ++c) region.center[c] = r["center"][static_cast<std::size_t>(c)].get<double>();
    region.radius = r.value("radius", 1e30);
    region.min_radius = r.value("min_radius", 0.0);
    regions.push_back(std::move(region));
  }
  return regions;
}

json region_json(const reference::RegionMean& m) {
  return {{"mean", {m.mean.x, m.mean.y, m.mean.z}},
          {"standard_error", {m.standard_error.x, m.standard_error.y, m.standard_error.z}},
          {"display", m.display}};
}

// The name of a bench image under images/: the run, the variant id (empty for the run's own images: its references
// and regions) and what the image shows (empty for the variant's own image), joined by '+', which run names and
// variant ids cannot hold (bench_config.cpp). Every image of a bench has a name of its own: run "x" with variant
// "y_f1" is x+y_f1.png, run "x_y" with variant "f1" x_y+f1.png; the run's reference is x++reference_volpath.png.
std::string image_name(const std::string& run, const std::string& variant, const std::string& what,
                       const char* extension) {
  return fmt::format("{}+{}{}{}{}", run, variant, what.empty() ? "" : "+", what, extension);
}

// One rendered variant, waiting for its comparison with the references.
struct Rendered {
  json result;
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> region_masks;  // name, mask
  ImageRGBA32F image;
  Scene scene;
  std::string scene_path, run, id;  // its run's name and its variant id, which name its images
  std::vector<std::string> sets;
  double wall_seconds = 0.0;
};

struct Bench {
  json config;
  std::vector<std::string> command_line_sets;  // --set
  fs::path out;
  std::unique_ptr<GLContext> context;

  // A cached reference with at least `spp` samples per pixel (reference/reference_cache.h), under out/references.
  reference::ReferenceImage reference_image(const std::string& scene_path, const std::vector<std::string>& sets,
                                            const std::string& integrator, int spp) {
    // A refinement step can take an hour: the same progress bar and time left as `lucent reference`.
    ProgressBar progress(fmt::format("  reference {} {} spp", integrator, spp), 1000);
    reference::ReferenceImage image =
        reference::cached_reference((out / "references").string(), scene_path, sets, integrator, spp,
                                    [&](double done) { progress.update_fraction(done); });
    progress.finish();
    return image;
  }

  // BSSRDF reference with as many 1-spp passes as fit in `seconds`.
  reference::ReferenceImage equal_time_reference(const Scene& scene, double seconds) {
    reference::ReferenceSettings settings;
    settings.integrator = reference::Integrator::Bssrdf;
    settings.samples_per_pixel = 1;
    settings.seed = 977;
    reference::ReferenceImage image = reference::render_reference(scene, settings);
    while (image.seconds < seconds) {
      reference::ReferenceImage more = reference::render_reference(scene, settings, &image);
      more.seconds += image.seconds;
      image = std::move(more);
    }
    return image;
  }

  Rendered render_variant(const json& run, const json& variant, const std::string& run_name) {
    Rendered r;
    r.sets = variant_overrides(config, run, variant, command_line_sets);
    r.scene_path = run.at("scene");
    r.scene = load_scene(r.scene_path, r.sets);
    const Scene& scene = r.scene;
    int frames = variant.value("frames", scene.render.frames);
    std::string name = variant.value("name", "default");
    fmt::print(stderr, "{} / {}: {} frame(s)\n", run_name, name, frames);

    Renderer renderer(scene);
    OffscreenFramebuffer target(scene.render.width, scene.render.height);
    // Warm-up frames (shader compilation, first-use driver costs) are rendered and thrown away, then the method
    // restarts: a measured 1-frame variant is the cost of an image after a scene change, not of a cold start.
    const int warmup = variant.value("warmup_frames", config.value("warmup_frames", 0));
    for (int f = 0; f < warmup; ++f) renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
    if (warmup > 0) {
      renderer.finished_frames(true);
      renderer.restart();
    }
    auto start = std::chrono::steady_clock::now();
    std::vector<FrameTimings> frames_done;
    // "restart_every_frame": every frame recomputes what the method caches (e.g. voxel-paths' solved volume, which
    // camera-only frames reuse), so the timings are those of a frame whose scene changed.
    const bool restart_every_frame = variant.value("restart_every_frame", run.value("restart_every_frame", false));
    for (int f = 0; f < frames; ++f) {
      if (restart_every_frame) renderer.restart();
      renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
      for (FrameTimings& t : renderer.finished_frames(false)) frames_done.push_back(std::move(t));
    }
    for (FrameTimings& t : renderer.finished_frames(true)) frames_done.push_back(std::move(t));
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The first frame is a warm-up (driver compiles, first-use costs) when there are others.
    std::span<const FrameTimings> measured(frames_done);
    if (measured.size() > 1) measured = measured.subspan(1);
    const FrameTimings& last = frames_done.back();
    r.image = renderer.read_radiance();
    r.run = run_name;
    r.id = variant.value("id", name);
    write_exr((out / "images" / image_name(r.run, r.id, "", ".exr")).string(), r.image);
    write_png((out / "images" / image_name(r.run, r.id, "", ".png")).string(), renderer.read_display());

    json& result = r.result;
    const stats::FrameSummary summary = stats::summarize(measured);
    auto spread_json = [](const stats::Spread& s) { return json{{"median", s.median}, {"min", s.min}, {"max", s.max}}; };
    result = {{"run", run_name}, {"variant", name}, {"scene", r.scene_path}, {"frames", frames},
              {"image", "images/" + image_name(r.run, r.id, "", ".png")},
              {"wall_seconds", r.wall_seconds}, {"gpu_memory_mb", static_cast<double>(last.gpu_memory_bytes) / 1048576.0},
              {"method", scene.method},
              {"occupancy", last.stat("translucent_pixels") / (static_cast<double>(scene.render.width) * scene.render.height)},
              {"coverage", last.stat("coverage", 1.0)}, {"total_ms", spread_json(summary.total_ms)}};
    result["passes"] = json::object();
    for (const stats::NamedSpread& p : summary.passes) result["passes"][p.name] = spread_json(p.spread);
    result["stats"] = json::object();
    for (const stats::NamedSpread& s : summary.stats) result["stats"][s.name] = spread_json(s.spread);
    for (const auto& [key, value] : variant.items())
      if (key != "set" && key != "name" && key != "id") result["params"][key] = value;
    for (const std::string& s : r.sets) {  // method.X as X, other keys by their path (scale_mm, render.width, ...)
      std::string key = s.substr(0, s.find('='));
      if (key.rfind("method.", 0) == 0) key = key.substr(7);
      json value = json::parse(s.substr(s.find('=') + 1), nullptr, false);
      if (key == "method" && value.is_object()) {  // method={"name": ..., "N": 8}: a whole method block
        for (const auto& [k, v] : value.items())
          if (k != "name") result["params"][k] = v;
        continue;
      }
      result["params"][key] = std::move(value);
    }
    if (variant.value("equal_time", false)) result["equal_time_request"] = true;
    if (denoise::denoise_settings(scene.denoise).enabled) result["denoise"] = true;  // the stage after the method
    for (const reference::ImageRegion& region : run_regions(run)) {
      r.region_masks.emplace_back(region.name, reference::region_mask(scene, region));
      // The region drawn over the variant's image (green), to see which pixels it holds.
      ImageRGBA8 shown = to_display(r.image, scene.render.exposure);
      for (std::size_t i = 0; i < r.region_masks.back().second.size(); ++i)
        if (r.region_masks.back().second[i]) shown.pixels[4 * i + 1] = 255;
      write_png((out / "images" / image_name(run_name, "", "region_" + region.name, ".png")).string(), shown);
      const reference::RegionMean m = reference::region_mean(r.image, r.region_masks.back().second, scene.render.exposure);
      result["regions"][region.name] = {{"pixels", m.pixels}, {"method", region_json(m)}};
    }
    return r;
  }

  // Compares the variants of one run with one reference integrator. Variants that share a reference (same
  // image-relevant overrides) are compared together; with "noise_ratio" R in the reference's configuration, the
  // reference is extended (up to "max_spp") until its own noise is R times below the smallest noise-corrected
  // RMSE measured against it.
  void compare(std::vector<Rendered>& rendered, const std::string& run_name, const std::string& integrator,
               const json& spec) {
    std::map<std::string, std::vector<Rendered*>> groups;
    for (Rendered& r : rendered) groups[reference::reference_key(r.scene_path, r.sets, integrator)].push_back(&r);
    const double ratio = spec.value("noise_ratio", 0.0);
    // Below this RMSE (linear radiance; a lit surface is about 0.5) an error is invisible after 8-bit quantization:
    // a reference is not refined further to resolve it (a black object matching a black reference, for example).
    const double floor = spec.value("rmse_floor", 1e-3);
    const int first_spp = spec.value("spp", 256), max_spp = spec.value("max_spp", first_spp);
    for (auto& [key, group] : groups) {
      reference::ReferenceImage ref = reference_image(group[0]->scene_path, group[0]->sets, integrator, first_spp);
      std::vector<ImageError> errors;
      for (;;) {
        errors.clear();
        double smallest = 1e30, noise = 0.0;
        for (Rendered* r : group) {
          // A non-finite pixel in a method's image or the reference is an error naming the image, not a score.
          errors.push_back(image_error(
              r->image, ref.mean, &ref.standard_error,
              {fmt::format("run {}'s image {}", run_name, image_name(r->run, r->id, "", ".exr")),
               fmt::format("the {} reference of run {}", integrator, run_name),
               fmt::format("the {} reference's standard error of run {}", integrator, run_name)}));
          smallest = std::min(smallest, corrected_rmse(errors.back()));
          noise = noise_rgb(errors.back());
        }
        smallest = std::max(smallest, floor);
        if (ratio <= 0.0 || noise * ratio <= smallest || ref.samples_per_pixel >= max_spp) {
          if (ratio > 0.0 && noise * ratio > smallest)
            fmt::print(stderr, "  reference {} for {}: noise {:.5f} is not {}x below the smallest RMSE {:.5f} at max_spp {}\n",
                       integrator, run_name, noise, ratio, smallest, max_spp);
          break;
        }
        // The standard error falls as 1/sqrt(spp): aim 10% past the predicted sample count, but at most double
        // per step, so every step is written to the cache and an interrupted run resumes where it stopped.
        const double current = ref.samples_per_pixel;
        double wanted = current * 1.1 * std::pow(noise * ratio / std::max(smallest, 1e-9), 2.0);
        int spp = static_cast<int>(std::min<double>(
            max_spp, std::max(current + 1.0, std::ceil(std::clamp(wanted, 1.25 * current, 2.0 * current)))));
        ref = reference_image(group[0]->scene_path, group[0]->sets, integrator, spp);
      }
      for (std::size_t i = 0; i < group.size(); ++i) attach_error(*group[i], run_name, integrator, ref, errors[i]);
    }
  }

  void attach_error(Rendered& r, const std::string& run_name, const std::string& integrator,
                    const reference::ReferenceImage& ref, const ImageError& e) {
    const Scene& scene = r.scene;
    const std::string model =
        integrator == "bssrdf"
            ? "_" + std::string(to_string(scene.objects[0].material ? scene.objects[0].material->model
                                                                    : kDefaultBssrdfModel))
            : "";
    std::string ref_png = "images/" + image_name(run_name, "", "reference_" + integrator + model, ".png");
    write_png((out / ref_png).string(), to_display(ref.mean, scene.render.exposure));
    write_png((out / "images" / image_name(r.run, r.id, "vs_" + integrator, ".png")).string(),
              heat_map(r.image, ref.mean, std::max(1e-6, 4.0 * e.rmse_rgb)));
    r.result["error"][integrator] = {{"rmse_rgb", e.rmse_rgb}, {"rmse", {e.rmse[0], e.rmse[1], e.rmse[2]}},
                                     {"rmse_rgb_corrected", corrected_rmse(e)},
                                     {"relative_mse", e.relative_mse}, {"mean_error", e.mean_error},
                                     {"mean_error_se", e.mean_error_se},
                                     {"reference_noise_rms", e.reference_noise_rms},
                                     {"reference_spp", ref.samples_per_pixel}, {"reference_seconds", ref.seconds},
                                     {"reference_image", ref_png}};
    for (const auto& [name, mask] : r.region_masks)
      r.result["regions"][name][integrator] =
          region_json(reference::region_mean(ref.mean, mask, scene.render.exposure, &ref.standard_error));
    if (integrator == "bssrdf" && r.result.value("equal_time_request", false)) {
      reference::ReferenceImage quick = equal_time_reference(scene, r.wall_seconds);
      ImageError eq = image_error(quick.mean, ref.mean, &ref.standard_error);
      r.result["equal_time_bssrdf"] = {{"rmse_rgb", eq.rmse_rgb}, {"spp", quick.samples_per_pixel},
                                       {"seconds", quick.seconds}};
      write_png((out / "images" / image_name(r.run, r.id, "equal_time_bssrdf", ".png")).string(),
                to_display(quick.mean, scene.render.exposure));
    }
  }

  // All variants of a run, then their comparison with each configured reference.
  void run(const json& run, const std::string& run_name, json& results) {
    std::vector<Rendered> rendered;
    for (const json& v : run_variants(config, run)) {
      if (config.value("record_refusals", false)) {
        // A method that cannot render this scene (no UVs, a deforming object, too many form factors, ...) refuses
        // with one line: recorded as the variant's result, so a matrix of every method over every scene runs on.
        try {
          rendered.push_back(render_variant(run, v, run_name));
        } catch (const Error& e) {
          const std::string name = v.value("name", "default");
          fmt::print(stderr, "  {} / {}: refused: {}\n", run_name, name, e.what());
          const Scene scene = load_scene(run.at("scene").get<std::string>(), variant_overrides(config, run, v, command_line_sets));
          results.push_back({{"run", run_name}, {"variant", name}, {"scene", run.at("scene")}, {"method", scene.method},
                             {"refused", e.what()}});
        }
      } else {
        rendered.push_back(render_variant(run, v, run_name));
      }
    }
    const json references = config.value("references", json::object());
    for (const auto& [integrator, spec] : references.items()) {
      if (spec.contains("only_runs") &&
          std::find(spec["only_runs"].begin(), spec["only_runs"].end(), run_name) == spec["only_runs"].end())
        continue;
      compare(rendered, run_name, integrator, spec);
    }
    for (Rendered& r : rendered) {
      r.result.erase("equal_time_request");
      results.push_back(std::move(r.result));
    }
  }
};

// Median ms of every pass and median of every statistic, "name value; ..." (what the method declares).
std::string spread_list(const json& r, const char* key) {
  std::string out;
  if (!r.contains(key)) return "-";
  for (const auto& [name, spread] : r[key].items())
    out += fmt::format("{}{} {:.4g}", out.empty() ? "" : "; ", name, spread["median"].get<double>());
  return out.empty() ? "-" : out;
}

std::string markdown(const json& results) {
  std::string md = "| run | variant | method | frames | total ms (median [min, max]) | passes (median ms) | "
                   "statistics (median) | GPU MB | coverage | RMSE vs bssrdf | RMSE vs volpath | mean error vs volpath | "
                   "equal-time bssrdf RMSE |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  // RMSE, the reference's own noise (and samples per pixel), and the noise-corrected RMSE.
  auto error = [](const json& r, const char* integrator) {
    if (!r.contains("error") || !r["error"].contains(integrator)) return std::string("-");
    const json& e = r["error"][integrator];
    ImageError ie;
    ie.rmse_rgb = e["rmse_rgb"].get<double>(), ie.reference_noise_rms = e["reference_noise_rms"].get<double>();
    return fmt::format("{:.4f} (ref noise {:.4f} at {} spp; corrected {:.4f})", ie.rmse_rgb, noise_rgb(ie),
                       e["reference_spp"].get<int>(), corrected_rmse(ie));
  };
  auto bias = [](const json& r, const char* integrator) {
    if (!r.contains("error") || !r["error"].contains(integrator)) return std::string("-");
    const json& e = r["error"][integrator];
    return fmt::format("{:+.4f} +- {:.4f}", e["mean_error"].get<double>(), e["mean_error_se"].get<double>());
  };
  for (const json& r : results) {
    if (r.contains("refused")) {
      md += fmt::format("| {} | {} | {} | refused: {} | | | | | | | | | |\n", r["run"].get<std::string>(),
                        r["variant"].get<std::string>(), r.value("method", std::string("?")),
                        r["refused"].get<std::string>());
      continue;
    }
    md += fmt::format("| {} | {} | {} | {} | {:.2f} [{:.2f}, {:.2f}] | {} | {} | {:.1f} | {:.3f} | {} | {} | {} | {} |\n",
                      r["run"].get<std::string>(), r["variant"].get<std::string>(), r.value("method", std::string("?")),
                      r["frames"].get<int>(), r["total_ms"]["median"].get<double>(), r["total_ms"]["min"].get<double>(),
                      r["total_ms"]["max"].get<double>(), spread_list(r, "passes"), spread_list(r, "stats"),
                      r["gpu_memory_mb"].get<double>(), r.value("coverage", 1.0), error(r, "bssrdf"),
                      error(r, "volpath"), bias(r, "volpath"),
                      r.contains("equal_time_bssrdf")
                          ? fmt::format("{:.4f} ({} spp)", r["equal_time_bssrdf"]["rmse_rgb"].get<double>(),
                                        r["equal_time_bssrdf"]["spp"].get<int>())
                          : "-");
  }
  // The regions: mean linear radiance (R, G, B) and the mean tone-mapped 8-bit value, method and references.
  bool any_region = false;
  for (const json& r : results) any_region = any_region || r.contains("regions");
  if (!any_region) return md;
  md += "\n| run | variant | region (pixels) | method: mean R, G, B (8-bit) | bssrdf reference | volpath reference |\n"
        "|---|---|---|---|---|---|\n";
  auto mean = [](const json& region, const char* who) {
    if (!region.contains(who)) return std::string("-");
    const json& m = region[who];
    const json& se = m["standard_error"];
    const bool noisy = se[0].get<double>() + se[1].get<double>() + se[2].get<double>() > 0.0;
    return fmt::format("{:.5f}, {:.5f}, {:.5f}{} ({:.1f}/255)", m["mean"][0].get<double>(), m["mean"][1].get<double>(),
                       m["mean"][2].get<double>(),
                       noisy ? fmt::format(" +- {:.5f}", std::max({se[0].get<double>(), se[1].get<double>(),
                                                                  se[2].get<double>()}))
                             : "",
                       m["display"].get<double>());
  };
  for (const json& r : results) {
    if (!r.contains("regions")) continue;
    for (const auto& [name, region] : r["regions"].items())
      md += fmt::format("| {} | {} | {} ({}) | {} | {} | {} |\n", r["run"].get<std::string>(),
                        r["variant"].get<std::string>(), name, region["pixels"].get<int>(), mean(region, "method"),
                        mean(region, "bssrdf"), mean(region, "volpath"));
  }
  return md;
}

// One line per result, with a header row naming the columns (gnuplot reads them by name): run, variant, method,
// median total ms, coverage, occupancy, the RMSEs, then every parameter any variant sets, the median ms of every
// pass ("ms:<pass>") and the median of every statistic ("stat:<name>"), "nan" where a result has none.
std::string tsv_text(const json& results) {
  std::vector<std::string> params, passes, statistics;
  auto add = [](std::vector<std::string>& list, const std::string& name) {
    if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
  };
  for (const json& r : results) {
    if (r.contains("params"))
      for (const auto& [k, v] : r["params"].items())
        if (v.is_number() || v.is_boolean()) add(params, k);
    if (r.contains("passes"))
      for (const auto& [k, v] : r["passes"].items()) add(passes, k);
    if (r.contains("stats"))
      for (const auto& [k, v] : r["stats"].items()) add(statistics, k);
  }
  std::ostringstream tsv;
  tsv << "run\tvariant\tmethod\ttotal_ms\tcoverage\toccupancy\trmse_bssrdf\trmse_volpath\trmse_equal_time_bssrdf";
  for (const std::string& p : params) tsv << "\t" << p;
  for (const std::string& p : passes) tsv << "\tms:" << p;
  for (const std::string& s : statistics) tsv << "\tstat:" << s;
  tsv << "\n";
  auto number = [](const json& j) { return j.is_boolean() ? std::string(j.get<bool>() ? "1" : "0") : j.dump(); };
  for (const json& r : results) {
    if (r.contains("refused")) continue;  // listed in results.md and results.json
    auto err = [&](const char* k) {
      return r.contains("error") && r["error"].contains(k) ? std::to_string(r["error"][k]["rmse_rgb"].get<double>()) : "nan";
    };
    tsv << r["run"].get<std::string>() << "\t" << r["variant"].get<std::string>() << "\t"
        << r.value("method", std::string("?")) << "\t" << r["total_ms"]["median"].get<double>() << "\t"
        << r.value("coverage", 1.0) << "\t" << r.value("occupancy", 0.0) << "\t" << err("bssrdf") << "\t"
        << err("volpath") << "\t"
        << (r.contains("equal_time_bssrdf") ? std::to_string(r["equal_time_bssrdf"]["rmse_rgb"].get<double>()) : "nan");
    for (const std::string& p : params)
      tsv << "\t" << (r.contains("params") && r["params"].contains(p) ? number(r["params"][p]) : "nan");
    for (const std::string& p : passes)
      tsv << "\t" << (r.contains("passes") && r["passes"].contains(p) ? std::to_string(r["passes"][p]["median"].get<double>()) : "nan");
    for (const std::string& st : statistics)
      tsv << "\t" << (r.contains("stats") && r["stats"].contains(st) ? std::to_string(r["stats"][st]["median"].get<double>()) : "nan");
    tsv << "\n";
  }
  return tsv.str();
}

// The runs to execute: all, or those named by --run (in the configuration's order). A name that is not a run of the
// configuration is an error naming it and the runs there are.
std::vector<std::size_t> selected_runs(const json& runs, const std::vector<std::string>& only,
                                       const std::string& config_path) {
  std::vector<std::string> names;
  for (const json& r : runs) names.push_back(run_name(r));
  for (const std::string& name : only)
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw Error(fmt::format("{}: --run {}: no such run; runs: {}", config_path, name, fmt::join(names, ", ")));
  std::vector<std::size_t> selected;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (only.empty() || std::find(only.begin(), only.end(), names[i]) != only.end()) selected.push_back(i);
  return selected;
}

void run(const std::string& config_path, const std::string& output, const std::vector<std::string>& only,
         const std::vector<std::string>& sets) {
  require_regular_file(config_path);
  std::ifstream file(config_path);
  if (!file) throw Error(fmt::format("{}: cannot open bench configuration", config_path));
  Bench bench;
  bench.config = parse_json(file, config_path);
  validate_bench_config(bench.config, config_path);
  bench.command_line_sets = sets;
  const json& runs = bench.config["runs"];
  const std::vector<std::size_t> selected = selected_runs(runs, only, config_path);
  // Every variant's scene, with its overrides, is loaded once before anything renders: a bad override in the last
  // run is an error now, not after the references of the first runs.
  std::vector<std::string> inputs = {config_path};
  for (std::size_t i : selected) {
    const json& r = runs[i];
    const json variants = run_variants(bench.config, r);
    for (std::size_t v = 0; v < variants.size(); ++v) {
      try {
        const Scene scene = load_scene(r.at("scene").get<std::string>(), variant_overrides(bench.config, r, variants[v], sets));
        for (std::string& input : scene_input_files(scene)) inputs.push_back(std::move(input));
      } catch (const Error& e) {
        throw Error(fmt::format("{}: /runs/{}{}: {}", config_path, i,
                                r.contains("variants") ? fmt::format("/variants/{}", v) : "", e.what()));
      }
    }
  }
  bench.out = output.empty() ? fs::path("out/bench") / fs::path(config_path).stem() : fs::path(output);
  const std::vector<OutputPath> table_paths = {{(bench.out / "results.json").string(), "--output", {}},
                                               {(bench.out / "results.md").string(), "--output", {}},
                                               {(bench.out / "results.tsv").string(), "--output", {}}};
  std::vector<OutputPath> outputs = table_paths;
  outputs.push_back({(bench.out / "images" / "probe.png").string(), "--output (images)", {}});
  outputs.push_back({(bench.out / "references" / "probe.exr").string(), "--output (reference cache)", {}});
  check_outputs(outputs, inputs);
  // The tables' lock stands for the folder: its images and reference cache are written by one bench at a time.
  const OutputLock lock(table_paths);
  bench.context = create_headless_context();
  json results = json::array();
  // The tables are rewritten after every run, so a long bench (references refined for hours) that is stopped
  // keeps the results of the runs it finished ("complete": false until the last one).
  auto write_results = [&](bool complete) {
    json doc = {{"config", config_path}, {"device", Renderer::device_of_current_context()}, {"complete", complete},
                {"results", results}};
    if (!only.empty()) doc["only_runs"] = only;  // --run: the other runs of the configuration were not run
    if (!sets.empty()) doc["set"] = sets;        // --set: every variant's scene had these overrides last
    // One set, each written beside and renamed over: a bench stopped mid-write leaves the previous complete files.
    OutputSet tables;
    tables.add((bench.out / "results.json").string(), doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
    tables.add((bench.out / "results.md").string(), markdown(results));
    tables.add((bench.out / "results.tsv").string(), tsv_text(results));
    tables.commit();
  };
  for (std::size_t k = 0; k < selected.size(); ++k) {
    const json& r = runs[selected[k]];
    bench.run(r, run_name(r), results);
    write_results(k + 1 == selected.size());
  }
  if (selected.empty()) write_results(true);
  for (const json& plot : bench.config.value("plots", json::array())) {
    std::string command = fmt::format("gnuplot -e \"tsv='{}'; out='{}'\" {}", (bench.out / "results.tsv").string(),
                                      (bench.out / plot.at("output").get<std::string>()).string(),
                                      plot.at("script").get<std::string>());
    if (std::system(command.c_str()) != 0) fmt::print(stderr, "lucent: warning: plot failed: {}\n", command);
  }
  fmt::print("{}\n{} -> {}\n", markdown(results), config_path, bench.out.string());
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto config = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto only = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("bench", "run a benchmark matrix (bench/*.json) against the CPU references");
  cmd->add_option("config", *config, "benchmark configuration (JSON), e.g. bench/accuracy.json")->required();
  cmd->add_option("-o,--output", *output, "output folder (default out/bench/<config name>)");
  add_no_cache_flag(cmd);
  cmd->add_option("--run", *only,
                  "run only this run of the configuration (repeatable); its references are cached and refined as in "
                  "the full matrix, e.g. --run grapefruit")
      ->allow_extra_args(false)  // one name per --run, so `bench --run a CONFIG` keeps CONFIG as the configuration
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  auto sets = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--set", *sets,
                  "override a scene value in every variant, after the configuration's own overrides (repeatable), "
                  "e.g. --set render.width=96; references are cached per override set")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->callback([config, output, only, sets] { run(*config, *output, *only, *sets); });
}

}  // namespace lucent::cli
