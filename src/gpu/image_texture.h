// image_texture.h: a 2D texture of one level, nearest filtering, clamped to its edges, labelled: per-texel images
// read with texelFetch or nearest lookups and written as images or attachments (the renderer's radiance and display
// images, the denoising stage's history and wavelet images, local-global's and the texture-space G-buffer's maps).
#pragma once
#include <string_view>

#include <epoxy/gl.h>

namespace lucent::gpu {

GLuint make_image_texture(int width, int height, GLenum format, std::string_view label);

}  // namespace lucent::gpu
