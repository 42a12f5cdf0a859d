// reference_renderer.h: renders a scene with one of the CPU references, progressively, deterministically from
// (seed, pixel, sample), producing the mean image and the per-pixel standard error.
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "lucent/image.h"
#include "lucent/scene.h"

namespace lucent::reference {

// The version of the references' estimators, recorded in every reference's metadata ("reference_version"; files
// without it are version 1). It is raised whenever a scene, seed and sample count render a different image: a
// reference of another version is never resumed, merged or reused from the cache, since its samples estimate
// something else. 2: self-intersection offsets relative to each hit (references no longer depend on the scene's
// size), every path's random numbers hashed from (seed, pixel, sample). 3: volpath's light through a refracting
// boundary from every specular chain with its exact geometry term (reference/boundary_light.h), where version 2
// followed one refracted path weighted as if the boundary were flat.
inline constexpr int kReferenceVersion = 3;

// A reference's version from its metadata (1 when absent).
int reference_version(const nlohmann::json& metadata);

enum class Integrator { Volpath, Bssrdf };
std::string_view to_string(Integrator integrator);

struct ReferenceSettings {
  Integrator integrator = Integrator::Volpath;
  int samples_per_pixel = 16;
  std::uint64_t seed = 1;
  int threads = 0;      // 0 = all cores
  bool jitter = false;  // false: rays through pixel centres, as the rasterizer samples
  double time_seconds = 0.0;  // animated scenes: the instant rendered
  // Volpath: paths end after this many scattering events in media (their last one's next-event estimate counted);
  // 0 = no limit. 1 restricts the image to single scattering (through refractive boundaries, internal Fresnel
  // reflections included), the physics of single-scattering methods.
  int max_scatter = 0;
  // --device gpu: a frame traces at most this many paths (one sample per pixel at least); a stop is seen and
  // progress reported between frames.
  double gpu_frame_paths = 32768.0;
  // Volpath: sphere jumps deep inside homogeneous media (docs/references.md, "Sphere jumps"): the same image, in
  // far fewer steps per path in dense, high-albedo media.
  bool sphere_jumps = true;
  // Both callbacks are called on the thread that called render_reference (never on a worker), between chunks of a
  // few rows times a few samples, sized to take about 20 ms each whatever the sample count: a stop is seen within
  // a chunk's time, and progress arrives as often.
  std::function<void(double done_fraction)> progress;
  // Called after each completed pass with the samples per pixel of this run in completed passes (what a stop would
  // keep), on the thread that called render_reference.
  std::function<void(int samples_done)> pass_done;
  // True stops the render, which returns the samples of the passes it completed (ReferenceImage::samples_per_pixel
  // tells how many; a pass is a few samples over every pixel, so the image stays a uniform number of samples per
  // pixel).
  std::function<bool()> stop_requested;
};

struct ReferenceImage {
  ImageRGBA32F mean;            // linear radiance; alpha = 1
  ImageRGBA32F standard_error;  // per channel standard error of the mean; alpha = 0
  int samples_per_pixel = 0;
  double seconds = 0.0;
  double steps_per_path = 0.0;  // volpath: mean walk steps per path of this run (paths of pixels that hit something)
  double steps_per_path_standard_error = 0.0;  // its standard error (paths independent)
};

// Renders `settings.samples_per_pixel` samples; with `previous`, adds them to its samples (sample indices
// continue after previous->samples_per_pixel, so two runs of S equal one run of 2S up to float rounding). The
// samples are rendered in passes over the whole image, each pass at most an eighth of the samples done before it
// (at least one): a stop (settings.stop_requested) keeps every completed pass. Stopped before the first pass ended,
// the result has the previous samples (none without `previous`: samples_per_pixel 0 and black images).
// The samples per pixel of the pass that follows `samples_before` samples (all runs' samples so far) when `remaining`
// are still wanted: an eighth of those before it, at least one, at most `remaining`. Few passes, and a stop loses at
// most an eighth of the work.
inline int reference_pass_size(int samples_before, int remaining) {
  return std::min(remaining, std::max(1, samples_before / 8));
}

ReferenceImage render_reference(const Scene& scene, const ReferenceSettings& settings,
                                const ReferenceImage* previous = nullptr);


// The camera ray through pixel (x + dx, y + dy), y = 0 the top row, matching the rasterizer's projection.
void camera_ray(const Camera& camera, int width, int height, double px, double py, glm::dvec3& origin,
                glm::dvec3& direction);

}  // namespace lucent::reference
