// reference_renderer.cpp: see reference_renderer.h.
#include "reference/reference_renderer.h"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "lucent/error.h"
#include "reference/embree_scene.h"
#include "reference/integrators.h"
#include "transport/rng.h"

namespace lucent::reference {

int reference_version(const nlohmann::json& metadata) {
  const auto found = metadata.find("reference_version");
  return found != metadata.end() && found->is_number_integer() ? found->get<int>() : 1;
}

std::string_view to_string(Integrator integrator) { return integrator == Integrator::Volpath ? "volpath" : "bssrdf"; }

void camera_ray(const Camera& camera, int width, int height, double px, double py, glm::dvec3& origin,
                glm::dvec3& direction) {
  glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target - camera.eye));
  glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
  glm::dvec3 up = glm::cross(right, forward);
  double tan_half = std::tan(glm::radians(static_cast<double>(camera.fov_y_deg)) / 2.0);
  double aspect = static_cast<double>(width) / height;
  double sx = (2.0 * px / width - 1.0) * tan_half * aspect;
  double sy = (1.0 - 2.0 * py / height) * tan_half;
  origin = camera.eye;
  direction = glm::normalize(forward + sx * right + sy * up);
}

namespace {

struct PixelSums {
  std::vector<glm::dvec3> sum, sum2;
};

PixelSums sums_from(const ReferenceImage& image) {
  std::size_t n = image.mean.pixels.size() / 4;
  PixelSums s{std::vector<glm::dvec3>(n), std::vector<glm::dvec3>(n)};
  double count = image.samples_per_pixel;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      double mean = image.mean.pixels[4 * i + static_cast<std::size_t>(c)];
      double se = image.standard_error.pixels[4 * i + static_cast<std::size_t>(c)];
      s.sum[i][c] = mean * count;
      s.sum2[i][c] = se * se * count * std::max(1.0, count - 1.0) + count * mean * mean;
    }
  return s;
}

using RadianceFunction = glm::dvec3 (*)(const ReferenceScene&, glm::dvec3, glm::dvec3, Rng&, const SurfaceHit*,
                                        PathRecord*);

struct PixelWork {
  std::int64_t paths = 0, steps = 0;  // paths traced (none for a background pixel); their walk steps
  double steps_squared = 0.0;         // the sum of each path's steps squared
};

// Samples [s0, s1) of pixel (x, y) added to its sums. Without jitter every
// sample's camera ray goes through the pixel centre: traced once here. A pixel whose ray misses everything shows the
// background, exactly, in every sample (both integrators), so its sums are written without sampling.
PixelWork render_pixel_samples(const ReferenceScene& rs, const ReferenceSettings& settings, RadianceFunction radiance,
                               int x, int y, int s0, int s1, glm::dvec3& sum, glm::dvec3& sum2) {
  const Scene& scene = rs.scene;
  const int width = scene.render.width, height = scene.render.height;
  const auto pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  glm::dvec3 centre_origin, centre_direction;
  SurfaceHit centre_hit;
  if (!settings.jitter) {
    camera_ray(scene.camera, width, height, x + 0.5, y + 0.5, centre_origin, centre_direction);
    centre_hit = rs.rt.intersect(centre_origin, centre_direction);
    if (!centre_hit.hit()) {
      const glm::dvec3 background(scene.render.background);
      const double count = s1 - s0;
      sum += count * background;
      sum2 += count * background * background;
      return {};
    }
  }
  std::int64_t steps = 0;
  double steps_squared = 0.0;
  for (int sample = s0; sample < s1; ++sample) {
    Rng rng = Rng::for_path(settings.seed, pixel, static_cast<std::uint64_t>(sample));
    glm::dvec3 L;
    PathRecord record;
    record.sample = sample;
    if (settings.jitter) {
      glm::dvec3 origin, direction;
      double jx = rng.uniform(), jy = rng.uniform();
      camera_ray(scene.camera, width, height, x + jx, y + jy, origin, direction);
      L = radiance(rs, origin, direction, rng, nullptr, &record);
    } else {
      L = radiance(rs, centre_origin, centre_direction, rng, &centre_hit, &record);
    }
    steps += record.steps;
    steps_squared += static_cast<double>(record.steps) * static_cast<double>(record.steps);
    if (!std::isfinite(L.x + L.y + L.z)) L = glm::dvec3(0.0);
    sum += L;
    sum2 += L * L;
  }
  return {s1 - s0, steps, steps_squared};
}

}  // namespace

ReferenceImage render_reference(const Scene& animated_scene, const ReferenceSettings& settings,
                                const ReferenceImage* previous) {
  // An animated scene is rendered as it stands at settings.time_seconds (deformations applied, blobs extracted).
  const Scene scene = scene_at_time(animated_scene, settings.time_seconds);
  const int width = scene.render.width, height = scene.render.height;
  if (settings.samples_per_pixel < 1) throw Error("--spp must be at least 1");
  if (previous && (previous->mean.width != width || previous->mean.height != height))
    throw Error(fmt::format("cannot add samples: the existing reference is {}x{}, the scene renders {}x{}",
                            previous->mean.width, previous->mean.height, width, height));
  if (settings.integrator == Integrator::Bssrdf)  // it integrates the models: they need what volpath does not
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
      if (scene.objects[i].material)
        validate_diffusion_medium(*scene.objects[i].material,
                                  fmt::format("{}: /objects/{}/material (the bssrdf reference)", scene.source, i));
  auto start = std::chrono::steady_clock::now();
  EmbreeScene rt(scene);
  if (settings.max_scatter < 0) throw Error("--max-scatter must be 0 (no limit) or more");
  ReferenceScene rs{scene, rt, settings.max_scatter};
  // One bank of canonical walks per sample index, generated on first use and dropped after its pass.
  SphereJumpBank jump_bank(settings.seed);
  rs.sphere_jumps = settings.sphere_jumps;
  if (settings.sphere_jumps) rs.jump_bank = &jump_bank;
  std::atomic<std::int64_t> total_steps{0}, total_paths{0};
  std::atomic<double> total_steps_squared{0.0};
  std::size_t pixels = static_cast<std::size_t>(width) * height;
  PixelSums sums = previous ? sums_from(*previous) : PixelSums{std::vector<glm::dvec3>(pixels), std::vector<glm::dvec3>(pixels)};
  const int first_sample = previous ? previous->samples_per_pixel : 0;
  const RadianceFunction radiance = settings.integrator == Integrator::Volpath ? volpath_radiance : bssrdf_radiance;

  std::unique_ptr<tbb::global_control> limit;
  if (settings.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, settings.threads);
  const int rows_per_chunk = std::max(1, height / 50);
  const int wanted = settings.samples_per_pixel;
  int done = 0;  // samples per pixel of this run in the sums, all of completed passes
  auto stop = [&] { return settings.stop_requested && settings.stop_requested(); };
  // A chunk is a few rows times a few samples of the pass; its sample count adapts so that a chunk takes about
  // kChunkSeconds, the most time between two polls of stop_requested (and two progress calls) whatever the spp.
  // Each pixel still adds its samples in order, so the sums do not depend on the chunking.
  constexpr double kChunkSeconds = 0.02;
  int batch = 1;
  while (done < wanted) {
    const int pass = reference_pass_size(first_sample + done, wanted - done);
    const int pass_first = first_sample + done, pass_end = pass_first + pass;
    const PixelSums before = sums;  // restored when the pass is stopped part-way
    bool complete = true;
    for (int row0 = 0; row0 < height && complete; row0 += rows_per_chunk) {
      const int row1 = std::min(height, row0 + rows_per_chunk);
      for (int s0 = pass_first; s0 < pass_end;) {
        if (stop()) {
          complete = false;
          break;
        }
        const int s1 = std::min(pass_end, s0 + batch);
        const auto chunk_start = std::chrono::steady_clock::now();
        tbb::parallel_for(row0 * width, row1 * width, [&](int index) {
          const auto pixel = static_cast<std::size_t>(index);
          const PixelWork work = render_pixel_samples(rs, settings, radiance, index % width, index / width, s0, s1,
                                                      sums.sum[pixel], sums.sum2[pixel]);
          if (work.paths > 0) {
            total_steps += work.steps, total_paths += work.paths;
            for (double seen = total_steps_squared.load();
                 !total_steps_squared.compare_exchange_weak(seen, seen + work.steps_squared);) {
            }
          }
        });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - chunk_start).count();
        if (seconds < 0.5 * kChunkSeconds && batch < (1 << 20)) batch *= 2;
        else if (seconds > 2.0 * kChunkSeconds && batch > 1) batch /= 2;
        s0 = s1;
        if (settings.progress) {
          const double pass_done = static_cast<double>(row0) / height +
                                   static_cast<double>(s1 - pass_first) / pass * (row1 - row0) / height;
          settings.progress((done + pass * pass_done) / static_cast<double>(wanted));
        }
      }
    }
    if (!complete) {
      sums = before;
      break;
    }
    done += pass;
    jump_bank.release_samples_before(pass_end);
    if (settings.pass_done) settings.pass_done(done);
  }
  const int total_samples = first_sample + done;

  ReferenceImage out;
  out.samples_per_pixel = total_samples;
  out.mean = {width, height, std::vector<float>(pixels * 4)};
  out.standard_error = {width, height, std::vector<float>(pixels * 4)};
  const double n = total_samples;
  for (std::size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < 3; ++c) {
      double mean = n > 0 ? sums.sum[i][c] / n : 0.0;
      double variance = n > 1 ? std::max(0.0, (sums.sum2[i][c] - n * mean * mean) / (n - 1.0)) : 0.0;
      out.mean.pixels[4 * i + static_cast<std::size_t>(c)] = static_cast<float>(mean);
      out.standard_error.pixels[4 * i + static_cast<std::size_t>(c)] = static_cast<float>(std::sqrt(variance / n));
    }
    out.mean.pixels[4 * i + 3] = 1.0f;
  }
  out.steps_per_path = total_paths > 0 ? static_cast<double>(total_steps) / static_cast<double>(total_paths) : 0.0;
  if (total_paths > 1) {
    const double paths = static_cast<double>(total_paths);
    const double variance = std::max(0.0, total_steps_squared.load() / paths - out.steps_per_path * out.steps_per_path);
    out.steps_per_path_standard_error = std::sqrt(variance / (paths - 1.0));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace lucent::reference
