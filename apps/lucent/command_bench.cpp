// command_bench.cpp: `lucent bench CONFIG`: a matrix of scenes x method variants, measured against the CPU
// references. Per variant: per-step GPU times (median and range over the frames after a warm-up frame),
// BSSRDF samples per second, GPU memory, coverage of the visible surface by the maps, and the error against the
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

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "image/image_metrics.h"
#include "lucent/lucent.h"
#include "reference/reference_renderer.h"

namespace lucent::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Stats {
  double median = 0.0, min = 0.0, max = 0.0;
};

Stats stats(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  std::size_t m = v.size() / 2;
  return {v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]), v.front(), v.back()};
}

std::vector<std::string> strings(const json& j, const char* key) {
  std::vector<std::string> out;
  if (j.contains(key))
    for (const auto& s : j.at(key)) out.push_back(s.get<std::string>());
  return out;
}

// Overrides that change the image of a reference: not method parameters or frame counts, and for volpath not
// the diffusion model either (the physics does not use it).
std::vector<std::string> relevant_overrides(const std::vector<std::string>& sets, const std::string& integrator) {
  std::vector<std::string> relevant;
  for (const std::string& s : sets) {
    bool method = s.rfind("method.", 0) == 0 || s.rfind("render.frames", 0) == 0;
    bool model = integrator == "volpath" && s.find(".model=") != std::string::npos;
    if (!method && !model) relevant.push_back(s);
  }
  std::sort(relevant.begin(), relevant.end());
  return relevant;
}

std::string reference_key(const std::string& scene, const std::vector<std::string>& sets, const std::string& integrator) {
  std::vector<std::string> relevant = relevant_overrides(sets, integrator);
  std::string text = scene + "|" + integrator;
  for (const std::string& s : relevant) text += "|" + s;
  return fmt::format("{}_{:016x}", integrator, std::hash<std::string>{}(text));
}

struct Bench {
  json config;
  fs::path out;
  std::unique_ptr<GLContext> context;

  // Renders (or loads) a reference with at least `spp` samples per pixel.
  reference::ReferenceImage reference_image(const std::string& scene_path, const std::vector<std::string>& sets,
                                            const std::string& integrator, int spp) {
    fs::path exr = out / "references" / (reference_key(scene_path, sets, integrator) + ".exr");
    fs::path meta = exr;
    meta.replace_extension(".json");
    fs::path se = reference::reference_sidecar(exr.string(), ".stderr.exr");
    // A cached reference of the same scene, integrator and image-relevant overrides (found by its metadata).
    if (fs::exists(exr.parent_path()))
      for (const auto& entry : fs::directory_iterator(exr.parent_path())) {
        if (entry.path().extension() != ".json") continue;
        json m = json::parse(std::ifstream(entry.path()), nullptr, false);
        if (m.is_discarded() || m.value("scene", "") != scene_path || m.value("integrator", "") != integrator) continue;
        if (relevant_overrides(m.value("overrides", std::vector<std::string>{}), integrator) !=
            relevant_overrides(sets, integrator))
          continue;
        fs::path cached_exr = entry.path();
        cached_exr.replace_extension(".exr");
        reference::ReferenceImage cached{read_exr(cached_exr.string()),
                                         read_exr(reference::reference_sidecar(cached_exr.string(), ".stderr.exr")),
                                         m["samples_per_pixel"], m["seconds"]};
        if (cached.samples_per_pixel >= spp) return cached;
      }
    Scene scene = load_scene(scene_path, sets);
    reference::ReferenceSettings settings;
    settings.integrator = integrator == "volpath" ? reference::Integrator::Volpath : reference::Integrator::Bssrdf;
    settings.samples_per_pixel = spp;
    fmt::print(stderr, "  reference {} {} spp ({}x{})...\n", integrator, spp, scene.render.width, scene.render.height);
    reference::ReferenceImage image = reference::render_reference(scene, settings);
    fs::create_directories(exr.parent_path());
    write_exr(exr.string(), image.mean);
    write_exr(se.string(), image.standard_error);
    std::ofstream(meta) << json{{"scene", scene_path}, {"overrides", sets}, {"integrator", integrator},
                                {"samples_per_pixel", image.samples_per_pixel}, {"seconds", image.seconds}}
                               .dump(2);
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

  double coverage(const Scene& scene_in) {
    Scene scene = scene_in;
    scene.method_params.set("view", std::string("coverage"));
    scene.method_params.set("progressive", false);
    Renderer renderer(scene);
    OffscreenFramebuffer target(scene.render.width, scene.render.height);
    renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
    ImageRGBA32F image = renderer.read_radiance();
    std::size_t covered = 0, uncovered = 0;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
      bool magenta = image.pixels[i] == 1.0f && image.pixels[i + 1] == 0.0f && image.pixels[i + 2] == 1.0f;
      bool gray = image.pixels[i] == 0.2f && image.pixels[i + 1] == 0.2f && image.pixels[i + 2] == 0.2f;
      uncovered += magenta, covered += gray;
    }
    return covered + uncovered ? static_cast<double>(covered) / static_cast<double>(covered + uncovered) : 1.0;
  }

  json run_variant(const json& run, const json& variant, const std::string& run_name) {
    std::vector<std::string> sets = strings(config, "set");
    for (const auto& s : strings(run, "set")) sets.push_back(s);
    for (const auto& s : strings(variant, "set")) sets.push_back(s);
    std::string scene_path = run.at("scene");
    Scene scene = load_scene(scene_path, sets);
    int frames = variant.value("frames", scene.render.frames);
    std::string name = variant.value("name", "default");
    fmt::print(stderr, "{} / {}: {} frame(s)\n", run_name, name, frames);

    Renderer renderer(scene);
    OffscreenFramebuffer target(scene.render.width, scene.render.height);
    std::vector<double> step1, step2, step3, total, rate;
    auto start = std::chrono::steady_clock::now();
    FrameTimings last;
    for (int f = 0; f < frames; ++f) {
      renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
      last = renderer.timings();
      if (frames > 1 && f == 0) continue;  // warm-up: driver compiles and first-use costs
      step1.push_back(last.light_gbuffer_ms), step2.push_back(last.radiosity_maps_ms);
      step3.push_back(last.combine_ms), total.push_back(last.total_ms);
      for (const StepTiming& s : last.passes)
        if (s.name == "integrate" && s.ms > 0) rate.push_back(static_cast<double>(last.bssrdf_samples) / (s.ms * 1e-3));
    }
    glFinish();
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ImageRGBA32F image = renderer.read_radiance();
    std::string stem = fmt::format("{}_{}", run_name, variant.value("id", name));
    std::replace_if(stem.begin(), stem.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '_'; }, '_');
    write_exr((out / "images" / (stem + ".exr")).string(), image);
    write_png((out / "images" / (stem + ".png")).string(), renderer.read_display());

    json result = {{"run", run_name}, {"variant", name}, {"frames", frames}, {"image", "images/" + stem + ".png"},
                   {"wall_seconds", wall}, {"gpu_memory_mb", static_cast<double>(last.gpu_memory_bytes) / 1048576.0},
                   {"bssrdf_samples_per_frame", last.bssrdf_samples}};
    for (auto [key, values] : {std::pair{"light_gbuffer_ms", step1}, std::pair{"radiosity_maps_ms", step2},
                               std::pair{"combine_ms", step3}, std::pair{"total_ms", total},
                               std::pair{"bssrdf_samples_per_second", rate}}) {
      Stats s = stats(values);
      result[key] = {{"median", s.median}, {"min", s.min}, {"max", s.max}};
    }
    for (const auto& [key, value] : variant.items())
      if (key != "set" && key != "name" && key != "id") result["params"][key] = value;
    for (const std::string& s : sets) {  // method.X as X, other keys by their path (scale_mm, render.width, ...)
      std::string key = s.substr(0, s.find('='));
      if (key.rfind("method.", 0) == 0) key = key.substr(7);
      result["params"][key] = json::parse(s.substr(s.find('=') + 1), nullptr, false);
    }
    if (variant.value("coverage", false)) result["coverage"] = coverage(scene);

    const json& refs = config.value("references", json::object());
    for (const auto& [integrator, spec] : refs.items()) {
      if (spec.contains("only_runs") && std::find(spec["only_runs"].begin(), spec["only_runs"].end(), run_name) == spec["only_runs"].end())
        continue;
      reference::ReferenceImage ref = reference_image(scene_path, sets, integrator, spec.value("spp", 256));
      ImageError e = image_error(image, ref.mean, &ref.standard_error);
      std::string ref_png = "images/" + run_name + "_reference_" + integrator +
                            (integrator == "bssrdf" ? "_" + std::string(to_string(scene.objects[0].material ? scene.objects[0].material->model : BssrdfModel::DirectionalDipole)) : "") + ".png";
      write_png((out / ref_png).string(), to_display(ref.mean, scene.render.exposure));
      write_png((out / "images" / (stem + "_vs_" + integrator + ".png")).string(),
                heat_map(image, ref.mean, std::max(1e-6, 4.0 * e.rmse_rgb)));
      result["error"][integrator] = {{"rmse_rgb", e.rmse_rgb}, {"rmse", {e.rmse[0], e.rmse[1], e.rmse[2]}},
                                     {"relative_mse", e.relative_mse}, {"mean_error", e.mean_error},
                                     {"mean_error_se", e.mean_error_se},
                                     {"reference_noise_rms", e.reference_noise_rms},
                                     {"reference_spp", ref.samples_per_pixel}, {"reference_image", ref_png}};
      if (integrator == "bssrdf" && variant.value("equal_time", false)) {
        reference::ReferenceImage quick = equal_time_reference(scene, wall);
        ImageError eq = image_error(quick.mean, ref.mean, &ref.standard_error);
        result["equal_time_bssrdf"] = {{"rmse_rgb", eq.rmse_rgb}, {"spp", quick.samples_per_pixel},
                                       {"seconds", quick.seconds}};
        write_png((out / "images" / (stem + "_equal_time_bssrdf.png")).string(), to_display(quick.mean, scene.render.exposure));
      }
    }
    return result;
  }
};

std::string markdown(const json& results) {
  std::string md = "| run | variant | frames | step 1 ms | step 2 ms | step 3 ms | total ms (median [min, max]) | "
                   "S_d samples/s | GPU MB | coverage | RMSE vs bssrdf | RMSE vs volpath | mean error vs volpath | "
                   "equal-time bssrdf RMSE |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  // RMSE, the reference's own noise, and the noise-corrected RMSE sqrt(max(0, RMSE^2 - noise^2)): the expected
  // squared error against a noisy reference is the method's squared error plus the reference's variance.
  auto error = [](const json& r, const char* integrator) {
    if (!r.contains("error") || !r["error"].contains(integrator)) return std::string("-");
    const json& e = r["error"][integrator];
    double rmse = e["rmse_rgb"].get<double>(), noise = e["reference_noise_rms"].get<double>() * std::sqrt(3.0);
    return fmt::format("{:.4f} (ref noise {:.4f}; corrected {:.4f})", rmse, noise,
                       std::sqrt(std::max(0.0, rmse * rmse - noise * noise)));
  };
  auto bias = [](const json& r, const char* integrator) {
    if (!r.contains("error") || !r["error"].contains(integrator)) return std::string("-");
    const json& e = r["error"][integrator];
    return fmt::format("{:+.4f} +- {:.4f}", e["mean_error"].get<double>(), e["mean_error_se"].get<double>());
  };
  for (const json& r : results) {
    md += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} [{:.2f}, {:.2f}] | {:.3g} | {:.1f} | {} | {} | {} | {} | {} |\n",
                      r["run"].get<std::string>(), r["variant"].get<std::string>(), r["frames"].get<int>(),
                      r["light_gbuffer_ms"]["median"].get<double>(), r["radiosity_maps_ms"]["median"].get<double>(),
                      r["combine_ms"]["median"].get<double>(), r["total_ms"]["median"].get<double>(),
                      r["total_ms"]["min"].get<double>(), r["total_ms"]["max"].get<double>(),
                      r["bssrdf_samples_per_second"]["median"].get<double>(), r["gpu_memory_mb"].get<double>(),
                      r.contains("coverage") ? fmt::format("{:.3f}", r["coverage"].get<double>()) : "-",
                      error(r, "bssrdf"), error(r, "volpath"), bias(r, "volpath"),
                      r.contains("equal_time_bssrdf")
                          ? fmt::format("{:.4f} ({} spp)", r["equal_time_bssrdf"]["rmse_rgb"].get<double>(),
                                        r["equal_time_bssrdf"]["spp"].get<int>())
                          : "-");
  }
  return md;
}

// One line per result: run, variant, every numeric parameter, median total ms, coverage, RMSEs.
void write_tsv(const json& results, const fs::path& path) {
  std::ofstream tsv(path);
  tsv << "run\tvariant\tK\tN\tscale_mm\ttotal_ms\tradiosity_maps_ms\tcoverage\trmse_bssrdf\trmse_volpath\trmse_equal_time_bssrdf\n";
  for (const json& r : results) {
    auto param = [&](const char* k) { return r.contains("params") && r["params"].contains(k) ? r["params"][k].dump() : "nan"; };
    auto err = [&](const char* k) {
      return r.contains("error") && r["error"].contains(k) ? std::to_string(r["error"][k]["rmse_rgb"].get<double>()) : "nan";
    };
    tsv << r["run"].get<std::string>() << "\t" << r["variant"].get<std::string>() << "\t" << param("K") << "\t"
        << param("N") << "\t" << param("scale_mm") << "\t" << r["total_ms"]["median"].get<double>() << "\t"
        << r["radiosity_maps_ms"]["median"].get<double>() << "\t"
        << (r.contains("coverage") ? std::to_string(r["coverage"].get<double>()) : "nan") << "\t" << err("bssrdf")
        << "\t" << err("volpath") << "\t"
        << (r.contains("equal_time_bssrdf") ? std::to_string(r["equal_time_bssrdf"]["rmse_rgb"].get<double>()) : "nan")
        << "\n";
  }
}

void run(const std::string& config_path, const std::string& output) {
  std::ifstream file(config_path);
  if (!file) throw Error(fmt::format("{}: cannot open bench configuration", config_path));
  Bench bench;
  bench.config = json::parse(file, nullptr, false, true);
  if (bench.config.is_discarded()) throw Error(fmt::format("{}: malformed JSON", config_path));
  bench.out = output.empty() ? fs::path("out/bench") / fs::path(config_path).stem() : fs::path(output);
  fs::create_directories(bench.out / "images");
  bench.context = create_headless_context();
  json results = json::array();
  for (const json& r : bench.config.at("runs")) {
    std::string run_name = r.value("name", fs::path(r.at("scene").get<std::string>()).stem().string());
    for (const json& v : r.value("variants", json::array({json::object()}))) results.push_back(bench.run_variant(r, v, run_name));
  }
  json doc = {{"config", config_path}, {"device", Renderer::device_of_current_context()}, {"results", results}};
  std::ofstream(bench.out / "results.json") << doc.dump(2) << "\n";
  std::ofstream(bench.out / "results.md") << markdown(results);
  write_tsv(results, bench.out / "results.tsv");
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
  CLI::App* cmd = app.add_subcommand("bench", "run a benchmark matrix (bench/*.json) against the CPU references");
  cmd->add_option("config", *config, "benchmark configuration (JSON), e.g. bench/accuracy.json")->required();
  cmd->add_option("-o,--output", *output, "output folder (default out/bench/<config name>)");
  cmd->callback([config, output] { run(*config, *output); });
}

}  // namespace lucent::cli
