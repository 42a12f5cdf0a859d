// image_texture.h: a 2D texture of one level, nearest filtering, labelled: the per-pixel images of a frame (the
// renderer's radiance and display images, the denoising stage's history and wavelet images), read with texelFetch
// and written as images.
#pragma once
#include <string_view>

#include <epoxy/gl.h>

namespace lucent::gpu {

GLuint make_image_texture(int width, int height, GLenum format, std::string_view label);

}  // namespace lucent::gpu
