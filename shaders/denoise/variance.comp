// variance.comp: the combined estimate divided by the albedo, and the variance of its luminance: the noise level the
// wavelet passes' luminance edge-stopping is measured against. From the temporal moments of one frame's luminance
// (temporal.comp) over the combined estimate's frames once at least kTemporalFrames lie behind the pixel; before
// that (after a restart or a disocclusion), from the spread of the combined estimate over the pixel's 5x5
// neighbourhood on the same surface (weights of denoise.glsl), which also holds the lighting's own variation there.
#include "denoise/denoise.glsl"

layout(binding = LUCENT_TEX_DENOISE_COMBINED) uniform sampler2D combined;
layout(binding = LUCENT_TEX_DENOISE_MOMENTS) uniform sampler2D moments;

const float kTemporalFrames = 4.0f;
layout(rgba32f, binding = LUCENT_IMAGE_DENOISE_OUTPUT) uniform writeonly image2D demodulated;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy), size = frame.output_size.xy;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  vec4 p = texelFetch(camera_position, pixel, 0);
  vec3 c = texelFetch(combined, pixel, 0).rgb;
  int object = pixel_object(p);
  if (object == 0) {
    imageStore(demodulated, pixel, vec4(c, 0.0f));
    return;
  }
  vec3 albedo = demodulation_albedo(object, pixel);
  vec4 sums = texelFetch(moments, pixel, 0);
  if (sums.z >= kTemporalFrames) {
    float mean = sums.x / sums.z;
    float frame_variance = max(sums.y / sums.z - mean * mean, 0.0f) * sums.z / (sums.z - 1.0f);
    imageStore(demodulated, pixel, vec4(c / albedo, frame_variance / max(texelFetch(combined, pixel, 0).a, 1.0f)));
    return;
  }
  vec3 n = texelFetch(camera_normal, pixel, 0).xyz;
  float sum = 0.0f, sum2 = 0.0f, weights = 0.0f;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 q_position = texelFetch(camera_position, q, 0);
      float w = geometry_weight(p, n, q_position, texelFetch(camera_normal, q, 0).xyz, max(length(vec2(dx, dy)), 1.0f));
      if (w <= 0.0f) continue;
      float l = luminance(texelFetch(combined, q, 0).rgb / albedo);
      sum += w * l;
      sum2 += w * l * l;
      weights += w;
    }
  float mean = sum / weights;
  float variance = max(sum2 / weights - mean * mean, 0.0f);
  imageStore(demodulated, pixel, vec4(c / albedo, variance));
}
