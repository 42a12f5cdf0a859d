// denoise_orbit.cpp: what the denoising stage gives a user who looks, then moves: STILL frames at the scene's camera,
// then one frame after the camera orbits DEGREES about its target (around the up axis). Writes, into OUT:
//   still_raw.exr, still_denoised.exr      the last still frame, raw and denoised
//   orbit_denoised.exr                     the first frame after the orbit, with the reprojected history
//   orbit_denoised_restart.exr             the same frame denoised from nothing (no history)
//   orbit_raw.exr                          the method's raw first frame at the new view (a restart)
//   orbit.json                             the scene at the new view (for `lucent reference`)
// and prints the flicker over the still frames (mean |change| between successive frames, raw and denoised) and the
// median cost of the stage against the median frame. Uses the public API only.
//
//   denoise_orbit SCENE OUT [STILL] [DEGREES] [key=value ...]   (defaults 16 frames, 5 degrees; further arguments are
//                                                                 --set overrides, e.g. render.width=96)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "lucent/lucent.h"
#include "lucent/scene_writer.h"

namespace {

double mean_change(const lucent::ImageRGBA32F& a, const lucent::ImageRGBA32F& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (i % 4 != 3) sum += std::fabs(a.pixels[i] - b.pixels[i]);
  return sum / static_cast<double>(a.pixels.size() / 4 * 3);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

lucent::ImageRGBA32F render(const lucent::Scene& scene, int frames) {
  lucent::OffscreenFramebuffer target(scene.render.width, scene.render.height);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < frames; ++f) renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
  return renderer.read_radiance();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: denoise_orbit SCENE OUT [STILL] [DEGREES] [key=value ...]\n");
    return 2;
  }
  try {
    auto context = lucent::create_headless_context();
    const std::string out = argv[2];
    const int still = argc > 3 ? std::stoi(argv[3]) : 16;
    const float degrees = argc > 4 ? std::stof(argv[4]) : 5.0f;
    std::vector<std::string> sets;
    for (int i = 5; i < argc; ++i) sets.push_back(argv[i]);
    std::filesystem::create_directories(out);
    sets.push_back("denoise.enabled=false");
    const lucent::Scene raw_scene = lucent::load_scene(argv[1], sets);
    sets.back() = "denoise.enabled=true";
    const lucent::Scene scene = lucent::load_scene(argv[1], sets);
    const int width = scene.render.width, height = scene.render.height;

    lucent::OffscreenFramebuffer target(width, height);
    lucent::Renderer raw(raw_scene), denoised(scene);
    lucent::ImageRGBA32F raw_previous, denoised_previous;
    double raw_change = 0.0, denoised_change = 0.0;
    std::vector<double> stage_ms, frame_ms;
    for (int f = 0; f < still; ++f) {
      raw.render(scene.camera, {target.id(), width, height});
      denoised.render(scene.camera, {target.id(), width, height});
      const lucent::ImageRGBA32F r = raw.read_radiance(), d = denoised.read_radiance();
      if (f > 0) raw_change += mean_change(r, raw_previous), denoised_change += mean_change(d, denoised_previous);
      raw_previous = r, denoised_previous = d;
    }
    for (const lucent::FrameTimings& t : denoised.finished_frames(true)) {
      double stage = 0.0;
      for (const lucent::PassTiming& p : t.passes)
        if (p.name.rfind("denoise_", 0) == 0) stage += p.ms;
      stage_ms.push_back(stage), frame_ms.push_back(t.total_ms);
    }
    lucent::write_exr(out + "/still_raw.exr", raw_previous);
    lucent::write_exr(out + "/still_denoised.exr", denoised_previous);

    lucent::Camera orbit = scene.camera;
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), orbit.up);
    orbit.eye = orbit.target + glm::vec3(turn * glm::vec4(orbit.eye - orbit.target, 0.0f));
    denoised.render(orbit, {target.id(), width, height});
    lucent::write_exr(out + "/orbit_denoised.exr", denoised.read_radiance());
    lucent::Scene at_orbit = scene;
    at_orbit.camera = orbit;
    lucent::write_exr(out + "/orbit_denoised_restart.exr", render(at_orbit, 1));
    lucent::Scene raw_at_orbit = raw_scene;
    raw_at_orbit.camera = orbit;
    lucent::write_exr(out + "/orbit_raw.exr", render(raw_at_orbit, 1));
    lucent::save_scene(raw_at_orbit, out + "/orbit.json");

    std::printf("flicker over %d still frames (mean |change| per pixel value): raw %.4g, denoised %.4g (%.1fx less)\n",
                still, raw_change / std::max(still - 1, 1), denoised_change / std::max(still - 1, 1),
                raw_change / std::max(denoised_change, 1e-30));
    std::printf("denoise stage: median %.2f ms of a median %.2f ms frame (%.1f%%), %dx%d\n", median(stage_ms),
                median(frame_ms), 100.0 * median(stage_ms) / std::max(median(frame_ms) - median(stage_ms), 1e-30),
                width, height);
    std::printf("orbit: %.1f degrees after %d frames; images in %s\n", degrees, still, out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "denoise_orbit: %s\n", e.what());
    return 1;
  }
}
