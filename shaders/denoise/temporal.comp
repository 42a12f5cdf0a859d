// temporal.comp: the method's average this frame combined with the history kept from before its last restart.
// A method averages its frames from its last restart; the stage keeps, per pixel, the combined estimate of the
// frame before that restart, reprojected into the new view (frozen: rgb H0, a its frames L0), and gives
//   c = (L0 H0 + N m) / (L0 + N)
// with m the method's average of N frames. While the view stays, N grows and the history's weight fades: a still
// view converges to the method's own average. At a camera move the previous frame's c is reprojected (bilinear
// over the four pixels around where the point was, each kept only on the same object, with a similar normal and
// on the point's tangent plane) with its frames capped at history_frames.
// Beside it, the moments of one frame's luminance / albedo (this frame's is N m - (N - 1) m_previous, exact while
// the method adds one frame to its average), reprojected and capped alike: the noise level the filter needs.
#include "denoise/denoise.glsl"

layout(binding = LUCENT_TEX_DENOISE_INPUT) uniform sampler2D method_average;
layout(binding = LUCENT_TEX_DENOISE_HISTORY) uniform sampler2D previous_combined;
layout(binding = LUCENT_TEX_DENOISE_PREVIOUS_POSITION) uniform sampler2D previous_position;
layout(binding = LUCENT_TEX_DENOISE_PREVIOUS_NORMAL) uniform sampler2D previous_normal;
layout(binding = LUCENT_TEX_DENOISE_PREVIOUS_AVERAGE) uniform sampler2D previous_average;
layout(binding = LUCENT_TEX_DENOISE_PREVIOUS_MOMENTS) uniform sampler2D previous_moments;
layout(rgba32f, binding = LUCENT_IMAGE_DENOISE_FROZEN) uniform image2D frozen;
layout(rgba32f, binding = LUCENT_IMAGE_DENOISE_OUTPUT) uniform writeonly image2D combined;
layout(rgba32f, binding = LUCENT_IMAGE_DENOISE_MOMENTS) uniform writeonly image2D moments;

// The previous frame's combined estimate (history) and moments at world point p (normal n), frames 0 (history.a,
// moments.z) where nothing there applies; both capped at history_frames.
void reproject(vec4 p, vec3 n, out vec4 history, out vec4 moment_sums) {
  history = vec4(0.0f);
  moment_sums = vec4(0.0f);
  vec4 clip = denoise.previous_clip_from_world * vec4(p.xyz, 1.0f);
  if (clip.w <= 0.0f) return;
  ivec2 size = frame.output_size.xy;
  vec2 at = (0.5f * clip.xy / clip.w + 0.5f) * vec2(size) - 0.5f;  // in pixel centres
  ivec2 base = ivec2(floor(at));
  vec2 f = at - vec2(base);
  float footprint = length(p.xyz - frame.camera_position.xyz) * denoise.weights.w;
  float weights = 0.0f;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = base + ivec2(i & 1, i >> 1);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    float w = ((i & 1) != 0 ? f.x : 1.0f - f.x) * ((i >> 1) != 0 ? f.y : 1.0f - f.y);
    vec4 q_position = texelFetch(previous_position, q, 0);
    vec3 q_normal = texelFetch(previous_normal, q, 0).xyz;
    // The previous pixel's point lies on this one's tangent plane within 2 footprints (a pixel's neighbours lie
    // within one), on the same object, with a normal within about 25 degrees.
    if (pixel_object(q_position) != pixel_object(p) || dot(q_normal, n) < 0.9f) continue;
    if (abs(dot(n, q_position.xyz - p.xyz)) > 2.0f * footprint) continue;
    vec4 c = texelFetch(previous_combined, q, 0);
    if (c.a <= 0.0f) continue;
    history += w * c;
    moment_sums += w * texelFetch(previous_moments, q, 0);
    weights += w;
  }
  if (weights < 1e-3f) {
    history = vec4(0.0f);
    moment_sums = vec4(0.0f);
    return;
  }
  history /= weights;
  moment_sums /= weights;
  float cap = denoise.history.x;
  history.a = min(history.a, cap);
  if (moment_sums.z > cap) moment_sums *= cap / moment_sums.z;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.output_size.x || pixel.y >= frame.output_size.y) return;
  vec4 m = texelFetch(method_average, pixel, 0);
  vec4 p = texelFetch(camera_position, pixel, 0);
  float n_frames = denoise.history.y;
  int object = pixel_object(p);
  if (object == 0) {  // the background: the method's value, no history
    imageStore(frozen, pixel, vec4(0.0f));
    imageStore(combined, pixel, vec4(m.rgb, n_frames));
    imageStore(moments, pixel, vec4(0.0f));
    return;
  }
  int state = denoise.state.x;
  vec4 kept = vec4(0.0f), moment_sums = vec4(0.0f);
  if (state == LUCENT_DENOISE_KEEP) {
    kept = imageLoad(frozen, pixel);
    moment_sums = texelFetch(previous_moments, pixel, 0);
  } else if (state == LUCENT_DENOISE_REPROJECT && denoise.history.x > 0.0f) {
    reproject(p, texelFetch(camera_normal, pixel, 0).xyz, kept, moment_sums);
  }
  if (state != LUCENT_DENOISE_KEEP) imageStore(frozen, pixel, kept);
  float frames = kept.a + n_frames;
  vec3 c = (kept.a * kept.rgb + n_frames * m.rgb) / max(frames, 1e-30f);
  imageStore(combined, pixel, vec4(c, frames));
  // This frame's own estimate: the method's average less what the previous frames had contributed to it.
  vec3 x = m.rgb;
  if (state == LUCENT_DENOISE_KEEP && n_frames >= 2.0f)
    x = n_frames * m.rgb - (n_frames - 1.0f) * texelFetch(previous_average, pixel, 0).rgb;
  float l = luminance(x / demodulation_albedo(object, pixel));
  imageStore(moments, pixel, moment_sums + vec4(l, l * l, 1.0f, 0.0f));
}
