// gpu_reference.cpp: see gpu_reference.h.
#include "render/gpu_reference.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"
#include "lucent/offscreen_framebuffer.h"
#include "lucent/renderer.h"
#include "methods/method_info.h"
#include "params/param_json.h"

namespace lucent::render {

reference::ReferenceImage render_reference_on_gpu(const Scene& scene_in, const reference::ReferenceSettings& settings,
                                                  std::string* device) {
  const methods::MethodInfo* method = methods::volpath_method();
  if (!method) throw Error("--device gpu: no registered method estimates the volpath image");
  if (settings.integrator != reference::Integrator::Volpath)
    throw Error("--device gpu: renders the volpath integrator only (the bssrdf reference runs on the CPU)");
  if (settings.jitter) throw Error("--device gpu: renders through pixel centres only; drop --jitter");
  Scene scene = scene_at_time(scene_in, settings.time_seconds);
  scene.method = std::string(method->name);
  scene.method_params = read_params(nlohmann::json::object(), {method->name, method->params}, {"--device gpu", ""});
  if (settings.samples_per_pixel < 2)
    throw Error(fmt::format("--spp {}: the GPU reference's standard error comes from the spread of its batches; give "
                            "at least 2 samples per pixel",
                            settings.samples_per_pixel));
  const int batches = std::min(kGpuReferenceBatches, settings.samples_per_pixel);
  // A batch is frames of equal size (a change of size would restart the accumulation), each at most
  // settings.gpu_frame_paths paths: a stop is seen and progress reported between frames, not once a batch.
  const double pixels = static_cast<double>(scene.render.width) * static_cast<double>(scene.render.height);
  int per_batch = (settings.samples_per_pixel + batches - 1) / batches;
  const int per_frame = std::clamp(static_cast<int>(settings.gpu_frame_paths / pixels), 1, per_batch);
  per_batch = (per_batch + per_frame - 1) / per_frame * per_frame;
  const int frames_per_batch = per_batch / per_frame;
  scene.method_params.set("samples_per_frame", static_cast<double>(per_frame));
  scene.method_params.set("sphere_jumps", settings.sphere_jumps);
  scene.method_params.set("max_scatter", static_cast<double>(settings.max_scatter));
  scene.denoise.set("enabled", false);  // a reference is the method's unbiased average
  scene.render.seed = settings.seed;  // every bit: seeds 1 and 2^32 are two random streams
  const int width = scene.render.width, height = scene.render.height;
  const std::size_t values = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;

  const auto start = std::chrono::steady_clock::now();
  Renderer renderer(scene);
  OffscreenFramebuffer target(width, height);
  // Batch b's mean from the running means before and after it (the accumulation continues the sample indices).
  std::vector<double> previous(values, 0.0), sum(values, 0.0), sum2(values, 0.0);
  ImageRGBA32F mean;
  double steps = 0.0;
  int done = 0;  // whole batches
  bool stopped = false;
  for (int b = 0; b < batches && !stopped; ++b) {
    double batch_steps = 0.0;
    for (int f = 0; f < frames_per_batch; ++f) {
      if (settings.stop_requested && settings.stop_requested()) {
        stopped = true;  // the batch's frames so far are not a batch: left out of the image
        break;
      }
      renderer.render(scene.camera, {target.id(), width, height});
      batch_steps += renderer.last_frame_timings().stat("steps_per_path", 0.0);
      const int frames_done = b * frames_per_batch + f + 1;
      if (settings.progress) settings.progress(static_cast<double>(frames_done) / (batches * frames_per_batch));
    }
    if (stopped) break;
    mean = renderer.read_radiance();
    for (std::size_t i = 0; i < values; ++i) {
      const double running = mean.pixels[i];
      const double batch = (running * (b + 1) - previous[i] * b);
      previous[i] = running;
      sum[i] += batch, sum2[i] += batch * batch;
    }
    steps += batch_steps / frames_per_batch;
    ++done;
    if (settings.pass_done) settings.pass_done(done * per_batch);
  }
  // One batch has no spread to give a standard error: nothing is kept (the command says none was saved).
  if (done < 2) done = 0;
  reference::ReferenceImage image;
  image.samples_per_pixel = done * per_batch;
  image.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  image.steps_per_path = done > 0 ? steps / done : 0.0;
  image.mean = ImageRGBA32F{width, height, std::vector<float>(values)};
  image.standard_error = ImageRGBA32F{width, height, std::vector<float>(values)};
  for (std::size_t i = 0; i < values; ++i) {
    if (i % 4 == 3) {
      image.mean.pixels[i] = 1.0f, image.standard_error.pixels[i] = 0.0f;
      continue;
    }
    const double m = done > 0 ? sum[i] / done : 0.0;
    const double variance = done > 1 ? std::max(0.0, (sum2[i] - done * m * m) / (done - 1)) : 0.0;
    image.mean.pixels[i] = static_cast<float>(m);
    image.standard_error.pixels[i] = static_cast<float>(std::sqrt(variance / std::max(done, 1)));
  }
  if (device) *device = renderer.device();
  return image;
}

}  // namespace lucent::render
