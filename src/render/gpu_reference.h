// gpu_reference.h: the volpath reference rendered on the GPU, by the registered method that estimates volpath's
// image (methods::volpath_method(), the random-walk method): the same mean and standard-error images, so batches
// from the GPU and the CPU merge (lucent reference --device gpu).
#pragma once
#include <string>

#include "lucent/scene.h"
#include "reference/reference_renderer.h"

namespace lucent::render {

// Renders `settings.samples_per_pixel` (rounded up to a multiple of the batch count) samples of the volpath image
// of `scene` through pixel centres with the current GL context. The standard error comes from the spread of
// kGpuReferenceBatches batch means per pixel (a batch is one frame of the method: its pixels share the frame's
// sphere-walk records, the batches are independent). settings.jitter, bssrdf and --resume are refused by the
// caller. `device` receives the GL renderer string.
inline constexpr int kGpuReferenceBatches = 16;
reference::ReferenceImage render_reference_on_gpu(const Scene& scene, const reference::ReferenceSettings& settings,
                                                  std::string* device = nullptr);

}  // namespace lucent::render
