// modulate.comp: the filtered radiance / albedo times the albedo again, weighed against the unfiltered combined
// estimate by fade^2 / (fade^2 + frames^2) (fade: denoise.history.z, 0 = no fade; frames: the combined estimate's,
// combined.a). The filter's bias falls as 1 / frames^2 while the noise it removes falls as 1 / sqrt(frames): a still
// view converges to the method's unbiased average, and the first tens of frames are filtered nearly in full.
// Written over the method's radiance image, keeping its coverage (alpha).
#include "denoise/denoise.glsl"

layout(binding = LUCENT_TEX_DENOISE_FILTER) uniform sampler2D filtered;
layout(binding = LUCENT_TEX_DENOISE_COMBINED) uniform sampler2D combined;
layout(rgba32f, binding = LUCENT_IMAGE_DENOISE_OUTPUT) uniform image2D hdr;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.output_size.x || pixel.y >= frame.output_size.y) return;
  float coverage = imageLoad(hdr, pixel).a;
  vec4 p = texelFetch(camera_position, pixel, 0);
  vec4 c = texelFetch(combined, pixel, 0);
  int object = pixel_object(p);
  vec3 radiance = c.rgb;
  if (object != 0) {
    float fade = denoise.history.z;
    float w = fade > 0.0f ? fade * fade / (fade * fade + c.a * c.a) : 1.0f;
    radiance = mix(c.rgb, demodulation_albedo(object, pixel) * texelFetch(filtered, pixel, 0).rgb, w);
  }
  imageStore(hdr, pixel, vec4(radiance, coverage));
}
