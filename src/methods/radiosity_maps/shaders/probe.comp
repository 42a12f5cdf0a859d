// probe.comp: the scattered radiosity B from the maps (Algorithm 1) at arbitrary surface points, for
// diagnostics and tests (symmetry, VPL energy).
#include "common/frame.glsl"
#include "methods/radiosity_maps/shaders/method_block.glsl"
#include "methods/radiosity_maps/shaders/map_lookup.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = LUCENT_BINDING_PROBES) buffer ProbeBlock { ProbeGPU probes[]; };
uniform int u_count;

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= u_count) return;
  probes[i].radiosity = combine_maps(probes[i].position.xyz, normalize(probes[i].normal.xyz));
}
