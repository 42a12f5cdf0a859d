// per_pixel.h: the caching-free baseline of Dal Corso et al. 2015, Fig. 11 ("no cache"): the light-space
// sampling of eq. 9 evaluated per screen pixel every frame, as translucent shadow maps do, instead of per map
// texel. Same light G-buffer (step 1) and estimator as radiosity-maps; cost grows with the pixels the
// translucent objects cover, which is what the break-even measurement of Fig. 11 varies.
// Shader: shaders/per_pixel/shade.comp.
#pragma once
#include <span>

#include "lucent/params.h"
#include "methods/method.h"

namespace lucent::methods {

std::span<const ParamDecl> per_pixel_params();
std::unique_ptr<Method> create_per_pixel(const Scene& scene, const render::SceneGpu& scene_gpu);

}  // namespace lucent::methods
