// tonemap.comp: linear HDR radiance -> display-referred 8-bit sRGB (operators in shared/tonemap.h).
#include "common/frame.glsl"
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = LUCENT_TEX_HDR) uniform sampler2D hdr;
layout(rgba8, binding = LUCENT_IMAGE_LDR) uniform writeonly image2D ldr;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.output_size.x || pixel.y >= frame.output_size.y) return;
  vec3 radiance = texelFetch(hdr, pixel, 0).rgb;
  imageStore(ldr, pixel, vec4(tonemap(radiance, frame.display.x, int(frame.display.y)), 1.0f));
}
