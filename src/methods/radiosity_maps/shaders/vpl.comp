// vpl.comp: places the virtual point lights (Dal Corso et al. 2015, Section 3.4). The translucent objects'
// outermost surface is rendered into a cube map about vpl_center (farthest depth wins); VPL v stands where the
// fixed direction u_v of a spherical Fibonacci set meets that surface, so positions stay put while the object
// deforms. Its area is A_v = (4 pi / N) |x_v - c|^2 / cos(u_v, n_v), the surface the direction's solid angle
// covers (sum over v: the outermost surface's area), and its radiosity B(x_v) comes from the maps (Algorithm 1).
#include "common/frame.glsl"
#include "methods/radiosity_maps/shaders/method_block.glsl"
#include "methods/radiosity_maps/shaders/map_lookup.glsl"
#include "bssrdf/constants.h"

layout(local_size_x = 64) in;

layout(binding = LUCENT_TEX_VPL_POSITION) uniform sampler2DArray vpl_position;
layout(binding = LUCENT_TEX_VPL_NORMAL) uniform sampler2DArray vpl_normal;
layout(std430, binding = LUCENT_BINDING_VPLS) writeonly buffer VplBlock { VplGPU vpls[]; };

void main() {
  int v = int(gl_GlobalInvocationID.x);
  int count = method.vpls.x;
  if (v >= count) return;
  // Spherical Fibonacci direction v of N.
  float z = 1.0f - (2.0f * float(v) + 1.0f) / float(count);
  float phi = 2.39996322972865f * float(v);  // golden angle
  float s = sqrt(max(0.0f, 1.0f - z * z));
  vec3 u = vec3(s * cos(phi), s * sin(phi), z);
  int face = cube_face(u);
  vec3 t = view_coords(method.vpl_views[face], method.vpl_center.xyz + u);
  int size = method.vpls.y;
  ivec3 texel = ivec3(clamp(ivec2(t.xy * float(size)), ivec2(0), ivec2(size - 1)), face);
  vec4 p = texelFetch(vpl_position, texel, 0);
  VplGPU vpl;
  vpl.position = vec4(0.0f);
  vpl.normal = vec4(0.0f, 0.0f, 1.0f, 1.0f);
  vpl.radiosity = vec4(0.0f);
  if (p.w > 0.5f) {
    vec3 n = normalize(texelFetch(vpl_normal, texel, 0).xyz);
    vec3 to_x = p.xyz - method.vpl_center.xyz;
    float cos_u = max(dot(u, n), 0.05f);  // grazing hits: bound the area a single VPL stands for
    float area = 4.0f * kPi / float(count) * dot(to_x, to_x) / cos_u;
    MaterialGPU material = materials[objects[int(p.w) - 1].info.x];
    vpl.position = vec4(p.xyz, area);
    vpl.normal = vec4(n, material.sigma_a.w);
    vpl.radiosity = vec4(combine_maps(p.xyz, n).rgb, 0.0f);
  }
  vpls[v] = vpl;
}
