// tissue_maps.h: layer thickness maps of organic tissue, generated procedurally (no external assets) or read from
// an image: an RGBA image whose channel j is the thickness of layer j as a fraction of the stack's depth, tiling
// seamlessly over [0, 1)^2. Used by the layered methods (subsurface texture mapping, multi-layer parallax).
#pragma once
#include <string>

#include "lucent/image.h"

namespace lucent::media {

// The procedural tissue stack, `size` x `size` texels, periodic over the image:
//   R  outer layer (epidermis-like): about 0.12 thick, thinner at pores (small round pits);
//   G  fat: round blobs (cellular noise), up to 0.3 thick, none between the blobs;
//   B  vessels: thin meandering lines (ridges of warped noise), up to 0.12 thick, none elsewhere;
//   A  deep tissue: what is left of the depth, 1 - (R + G + B), at least 0.
// Deterministic for a size.
ImageRGBA32F tissue_layer_maps(int size);

// Channel j of every texel is `thickness[j]` (one texel).
ImageRGBA32F uniform_layer_maps(float t0, float t1, float t2, float t3);

// A PNG (8-bit channels read linearly as value / 255, not as sRGB) or OpenEXR file. Throws lucent::Error naming the
// file when it cannot be read, is not .png/.exr, or holds a negative or non-finite value.
ImageRGBA32F read_layer_maps(const std::string& path);

// Surface textures of a two-layer tissue for multi-layer parallax shading (Oat 2006), derived from the same
// procedural stack, `size` x `size`, periodic:
//   outer_base   rgb: the outer layer's base colour (pale, yellow over fat); a: how much the outer layer lets the
//                inner one show (high between pores and fat, low over them)
//   outer_normal rgb: the outer layer's tangent-space unit normal (x along u, y along v, z out of the surface;
//                images top row first, v = 0 at the bottom row),
//                from the pores' and blobs' relief; a: 1
//   inner_base   rgb: the inner layer's base colour (red tissue, dark vessels); a: 1
struct TissueSurfaceTextures {
  ImageRGBA32F outer_base, outer_normal, inner_base;
};
TissueSurfaceTextures tissue_surface_textures(int size);

}  // namespace lucent::media
