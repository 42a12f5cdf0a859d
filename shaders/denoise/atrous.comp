// atrous.comp: one pass of the edge-stopping a-trous wavelet filter (Dammertz et al. 2010), guided as in SVGF
// (Schied et al. 2017): a 5x5 B3-spline kernel whose taps lie denoise.history.w pixels apart (1, 2, 4, ... over the
// passes), each weighted by the geometry (same object, normals, tangent plane: denoise.glsl) and by the luminance
// difference against sigma_luminance standard deviations of the pixel's estimated noise. The variance is filtered
// with the squared weights, so each pass measures against the noise left after the passes before it.
#include "denoise/denoise.glsl"

layout(binding = LUCENT_TEX_DENOISE_FILTER) uniform sampler2D source;  // rgb radiance / albedo, a: variance
layout(rgba32f, binding = LUCENT_IMAGE_DENOISE_OUTPUT) uniform writeonly image2D filtered;

const float kB3[3] = float[3](3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f);

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy), size = frame.output_size.xy;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  vec4 centre = texelFetch(source, pixel, 0);
  vec4 p = texelFetch(camera_position, pixel, 0);
  if (pixel_object(p) == 0) {
    imageStore(filtered, pixel, centre);
    return;
  }
  vec3 n = texelFetch(camera_normal, pixel, 0).xyz;
  int step = int(denoise.history.w);
  float l_p = luminance(centre.rgb);
  // The noise level the luminance differences are measured against: the variance blurred over the 3x3 pixels
  // around (a Gaussian, on the same object), as in SVGF, so that one pixel's estimate of it is not all it has.
  float blurred = 0.0f, blur_weights = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
      if (pixel_object(texelFetch(camera_position, q, 0)) != pixel_object(p)) continue;
      float w = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
      blurred += w * texelFetch(source, q, 0).a;
      blur_weights += w;
    }
  float variance_p = blurred / blur_weights;
  vec3 sum = vec3(0.0f);
  float variance = 0.0f, weights = 0.0f;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = pixel + step * ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 value = texelFetch(source, q, 0);
      float w = kB3[abs(dx)] * kB3[abs(dy)];
      if (dx != 0 || dy != 0) {
        w *= geometry_weight(p, n, texelFetch(camera_position, q, 0), texelFetch(camera_normal, q, 0).xyz,
                             float(step) * length(vec2(dx, dy)));
        // Measured against the larger of the two pixels' noise, so that p weighs q as q weighs p: with each pixel's
        // own, a bright pixel (more noise) took in its dark neighbours while they kept it out, which darkened the
        // image (by up to 2% of its mean on the leaderboard's marble bunny at 4 paths per pixel).
        float l_q = luminance(value.rgb);
        float tolerance = denoise.weights.x * sqrt(max(variance_p, value.a)) + 1e-6f * max(abs(l_p), abs(l_q)) + 1e-30f;
        w *= exp(-abs(l_q - l_p) / tolerance);
      }
      sum += w * value.rgb;
      variance += w * w * value.a;
      weights += w;
    }
  imageStore(filtered, pixel, vec4(sum / weights, variance / (weights * weights)));
}
