// blur.comp: one pass of the screen-space method's separable blur, along x (horizontal) or, with
// LUCENT_BLUR_VERTICAL defined, along y. Each translucent pixel takes its material's 1D kernel (screen_space_kernel.h:
// the Burley profile's marginal, weights per band summing to 1, offsets in scene units), projects the offsets to
// pixels at its own depth (the world-space offset divided by the pixel footprint there), reads each tap between the
// two pixels around it (linear interpolation) and sums the taps. A tap
// off the image or off a translucent surface takes the centre's value; a tap whose depth along the view ray differs
// from the centre's by d is blended back to the centre by min(1, d / (threshold * kernel radius)): the weights are
// never renormalised, so a flat, uniformly lit surface keeps its irradiance exactly.
#include "common/frame.glsl"
#include "methods/screen_space/screen_space_io.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { ScreenSpaceGPU method; };
layout(std430, binding = LUCENT_BINDING_SCREEN_SPACE_KERNEL) readonly buffer KernelBlock { ScreenSpaceTapGPU kernel[]; };
layout(binding = LUCENT_TEX_CAMERA_POSITION) uniform sampler2D camera_position;
#ifdef LUCENT_BLUR_VERTICAL
layout(rgba32f, binding = LUCENT_IMAGE_SCREEN_SPACE_HORIZONTAL) uniform readonly image2D source;
layout(rgba32f, binding = LUCENT_IMAGE_SCREEN_SPACE_BLURRED) uniform writeonly image2D target;
const ivec2 kAxis = ivec2(0, 1);
#else
layout(rgba32f, binding = LUCENT_IMAGE_SCREEN_SPACE_IRRADIANCE) uniform readonly image2D source;
layout(rgba32f, binding = LUCENT_IMAGE_SCREEN_SPACE_HORIZONTAL) uniform writeonly image2D target;
const ivec2 kAxis = ivec2(1, 0);
#endif

vec2 pixel_of(vec3 x) {
  vec4 clip = frame.clip_from_world * vec4(x, 1.0f);
  return (0.5f * clip.xy / clip.w + vec2(0.5f)) * vec2(frame.output_size.xy);
}

// The irradiance a tap at pixel q contributes to the centre x: the centre's own off the image or off a translucent
// surface, blended back to it with the depth difference along the view ray.
vec3 tap_value(ivec2 q, vec3 x, vec3 view, vec3 centre, float tolerance) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frame.output_size.xy))) return centre;
  vec4 s = imageLoad(source, q);
  if (s.a < 0.5f) return centre;
  float depth = abs(dot(texelFetch(camera_position, q, 0).xyz - x, view));
  return mix(s.rgb, centre, min(1.0f, depth / tolerance));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.output_size.x || pixel.y >= frame.output_size.y) return;
  vec4 centre = imageLoad(source, pixel);
  if (centre.a < 0.5f) {
    imageStore(target, pixel, centre);
    return;
  }
  vec4 p = texelFetch(camera_position, pixel, 0);
  int first = objects[int(p.w) - 1].info.x * LUCENT_SCREEN_SPACE_MAX_TAPS;
  int taps = method.counts.x;
  float radius = max(abs(kernel[first].tap.w), abs(kernel[first + taps - 1].tap.w));  // [scene units]
  // Pixels per scene unit at x: a displacement perpendicular to the view ray, projected.
  vec3 view = normalize(p.xyz - frame.camera_position.xyz);
  vec3 side = normalize(cross(view, abs(view.y) < 0.99f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f)));
  float probe = max(radius, 1e-6f);
  float pixels_per_unit = length(pixel_of(p.xyz + probe * side) - pixel_of(p.xyz)) / probe;
  float tolerance = max(method.blur.x * radius, 1e-12f);
  vec3 sum = vec3(0.0f);
  // loop bound: LUCENT_SCREEN_SPACE_MAX_TAPS; the kernel holds at most that many taps per material
  for (int j = 0; j < taps; ++j) {
    vec4 tap = kernel[first + j].tap;
    // The tap's offset in pixels, read between the two pixels around it (linear interpolation).
    float offset = tap.w * pixels_per_unit;
    float below = floor(offset);
    vec3 a = tap_value(pixel + kAxis * int(below), p.xyz, view, centre.rgb, tolerance);
    vec3 b = tap_value(pixel + kAxis * (int(below) + 1), p.xyz, view, centre.rgb, tolerance);
    sum += tap.rgb * mix(a, b, offset - below);
  }
  imageStore(target, pixel, vec4(sum, 1.0f));
}
