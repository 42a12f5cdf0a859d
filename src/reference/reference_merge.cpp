// reference_merge.cpp: see reference_merge.h.
#include "reference/reference_merge.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "cache/precompute_cache.h"
#include "lucent/error.h"
#include "lucent/output_file.h"
#include "reference/reference_cache.h"

namespace lucent::reference {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void hash_text(cache::Hasher& hasher, std::string_view text) {
  const std::uint64_t size = text.size();
  hasher.update(std::as_bytes(std::span<const std::uint64_t, 1>(&size, 1)));
  hasher.update(std::as_bytes(std::span<const char>(text.data(), text.size())));
}

// A setting that changes the image, with the value older metadata implies when it does not record it.
struct ImageSetting {
  const char* key;
  json absent;
};

json setting(const json& meta, const ImageSetting& s) { return meta.contains(s.key) ? meta[s.key] : s.absent; }

std::vector<std::string> overrides_of(const json& meta) {
  std::vector<std::string> sets;
  if (meta.contains("overrides") && meta["overrides"].is_array())
    for (const json& s : meta["overrides"])
      if (s.is_string()) sets.push_back(s.get<std::string>());
  const std::string integrator = meta.contains("integrator") && meta["integrator"].is_string()
                                     ? meta["integrator"].get<std::string>()
                                     : std::string();
  const std::string scene = meta.contains("scene") && meta["scene"].is_string() ? meta["scene"].get<std::string>() : "";
  return relevant_overrides(sets, integrator, scene);
}

}  // namespace

std::string scene_content_hash(const Scene& scene) {
  cache::Hasher hasher;
  for (const std::string& file : scene_input_files(scene)) {
    if (file.empty()) continue;
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(fmt::format("{}: cannot read (to record the scene's content in the metadata)", file));
    std::stringstream bytes;
    bytes << in.rdbuf();
    hash_text(hasher, bytes.str());
  }
  return hasher.finish().hex();
}

std::string scene_models(const Scene& scene) {
  std::string models;
  for (const SceneObject& object : scene.objects) {
    if (!object.translucent()) continue;
    if (!models.empty()) models += ",";
    models += to_string(object.material->model);
  }
  return models;
}

std::vector<std::uint64_t> reference_seeds(const json& meta, const std::string& path) {
  std::vector<std::uint64_t> seeds;
  auto add = [&](const json& seed) {
    if (!seed.is_number_integer() || (!seed.is_number_unsigned() && seed.get<long long>() < 0))
      throw Error(fmt::format("{}: malformed reference metadata: seed {} is not a whole number", path, seed.dump()));
    seeds.push_back(seed.get<std::uint64_t>());
  };
  if (meta.contains("seeds") && meta["seeds"].is_array() && !meta["seeds"].empty()) {
    for (const json& seed : meta["seeds"]) add(seed);
  } else if (meta.contains("seed")) {
    add(meta["seed"]);
  } else {
    throw Error(fmt::format("{}: no seed in the metadata: cannot tell whether its samples are independent of the "
                            "other inputs'",
                            path));
  }
  return seeds;
}

StoredReference merge_references(const std::vector<std::string>& inputs) {
  if (inputs.size() < 2) throw Error("reference merge: give two or more references to merge");
  struct Batch {
    std::string path;
    StoredReference stored;
    std::vector<std::uint64_t> seeds;
  };
  std::vector<Batch> batches;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string& path = inputs[i];
    for (std::size_t j = 0; j < i; ++j)
      if (same_file(path, inputs[j]))
        throw Error(fmt::format("{}: cannot merge: the same file as {} (a batch is not independent of itself)", path,
                                inputs[j]));
    const ReferenceFiles files = reference_files(path);
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(fmt::format("{}: no such file", path));
    if (!fs::exists(files.standard_error, ec))
      throw Error(fmt::format("{}: no such file (the standard error written beside {})", files.standard_error, path));
    Batch batch{path, load_reference(files), {}};
    batch.seeds = reference_seeds(batch.stored.metadata, files.metadata);
    batches.push_back(std::move(batch));
  }

  // The same image: every setting that changes it, and the same scene (by content where both record it).
  const Batch& first = batches.front();
  const json& m0 = first.stored.metadata;
  const ImageSetting settings[] = {{"integrator", json()},  {"width", json()},        {"height", json()},
                                   {"jitter", json(false)}, {"max_scatter", json(0)}, {"time_seconds", json(0.0)},
                                   {"reference_version", json(1)}};
  long long total = 0;
  double seconds = 0.0;
  for (std::size_t i = 0; i < batches.size(); ++i) {
    const Batch& b = batches[i];
    const json& m = b.stored.metadata;
    for (const ImageSetting& s : settings)
      if (setting(m, s) != setting(m0, s))
        throw Error(fmt::format("{}: cannot merge: {} {} differs from {} in {}", b.path, s.key, setting(m, s).dump(),
                                setting(m0, s).dump(), first.path));
    const bool hashed = m.contains("scene_hash") && m0.contains("scene_hash");
    const char* scene_key = hashed ? "scene_hash" : "scene";
    const ImageSetting scene{scene_key, json()};
    if (setting(m, scene) != setting(m0, scene))
      throw Error(fmt::format("{}: cannot merge: another scene ({} {} differs from {} in {})", b.path, scene_key,
                              setting(m, scene).dump(), setting(m0, scene).dump(), first.path));
    const auto models = [](const json& j) { return j.contains("models") ? j["models"] : json(); };
    if (models(m) != models(m0))
      throw Error(fmt::format("{}: cannot merge: the models {} differ from {} in {}", b.path, models(m).dump(),
                              models(m0).dump(), first.path));
    if (overrides_of(m) != overrides_of(m0))
      throw Error(fmt::format("{}: cannot merge: overrides {} differ from {} in {}", b.path, json(overrides_of(m)).dump(),
                              json(overrides_of(m0)).dump(), first.path));
    const ImageRGBA32F& mean = b.stored.image.mean;
    if (mean.width != first.stored.image.mean.width || mean.height != first.stored.image.mean.height)
      throw Error(fmt::format("{}: cannot merge: the image is {}x{}, {} is {}x{}", b.path, mean.width, mean.height,
                              first.path, first.stored.image.mean.width, first.stored.image.mean.height));
    for (std::size_t j = 0; j < i; ++j)
      for (std::uint64_t seed : b.seeds)
        for (std::uint64_t other : batches[j].seeds)
          if (seed == other)
            throw Error(fmt::format("{}: cannot merge: seed {} is also the seed of {} (batches need distinct seeds to "
                                    "be independent)",
                                    b.path, seed, batches[j].path));
    total += b.stored.image.samples_per_pixel;
    if (total > std::numeric_limits<int>::max())
      throw Error(fmt::format("{}: cannot merge: the samples per pixel would exceed {}", b.path,
                              std::numeric_limits<int>::max()));
    seconds += b.stored.image.seconds;
  }

  // Per pixel and channel: the renderer's estimator over all the samples (see the header).
  const int width = first.stored.image.mean.width, height = first.stored.image.mean.height;
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  StoredReference out;
  out.image.mean = {width, height, std::vector<float>(pixels * 4)};
  out.image.standard_error = {width, height, std::vector<float>(pixels * 4)};
  out.image.samples_per_pixel = static_cast<int>(total);
  out.image.seconds = seconds;
  const double N = static_cast<double>(total);
  // (load_reference refused any pixel whose mean or standard error is not finite and >= 0.)
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t k = 4 * p + c;
      double sum = 0.0;
      for (const Batch& b : batches) sum += b.stored.image.samples_per_pixel * static_cast<double>(b.stored.image.mean.pixels[k]);
      const double mean = sum / N;
      double m2 = 0.0;  // sum over all samples of (x - mean)^2
      for (const Batch& b : batches) {
        const double n = b.stored.image.samples_per_pixel, m = b.stored.image.mean.pixels[k],
                     s = b.stored.image.standard_error.pixels[k];
        m2 += s * s * n * (n - 1.0) + n * (m - mean) * (m - mean);
      }
      const double variance = N > 1.0 ? m2 / (N - 1.0) : 0.0;
      out.image.mean.pixels[k] = static_cast<float>(mean);
      out.image.standard_error.pixels[k] = static_cast<float>(std::sqrt(variance / N));
    }
    out.image.mean.pixels[4 * p + 3] = 1.0f;
  }

  json meta = m0;
  meta.erase("seed");
  meta.erase("camera_paths_per_second");
  // Per-run statistics and the sphere-jump setting (batches with and without jumps estimate the same image and
  // merge; each input records its own) are not the merged set's.
  meta.erase("steps_per_path");
  meta.erase("sphere_jumps");
  json seeds = json::array(), sources = json::array();
  for (const Batch& b : batches) {
    for (std::uint64_t seed : b.seeds) seeds.push_back(seed);
    sources.push_back({{"path", b.path},
                       {"scene", b.stored.metadata.contains("scene") ? b.stored.metadata["scene"] : json()},
                       {"seeds", b.seeds},
                       {"samples_per_pixel", b.stored.image.samples_per_pixel},
                       {"seconds", b.stored.image.seconds}});
    if (b.stored.metadata.contains("sphere_jumps")) sources.back()["sphere_jumps"] = b.stored.metadata["sphere_jumps"];
  }
  meta["seeds"] = seeds;
  meta["inputs"] = sources;
  if (seconds > 0.0) meta["camera_paths_per_second"] = static_cast<double>(pixels) * N / seconds;
  out.metadata = std::move(meta);
  return out;
}

}  // namespace lucent::reference
