// atlas_view.vert: the camera view of one translucent mesh, pulled from the scene's world-space vertex and index
// buffers (the camera G-buffer's geometry, so the same pixels are covered), with each corner's atlas coordinates
// and the radiosity B^d + B^g' of its global vertex (Gouraud interpolation, Lensch et al. 2002, Eq. 12).
#include "common/frame.glsl"
#include "methods/local_global/local_global_io.h"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LocalGlobalGPU method; };
layout(std430, binding = LUCENT_BINDING_LG_SCENE_VERTICES) readonly buffer VertexBlock { VertexGPU vertices[]; };
layout(std430, binding = LUCENT_BINDING_LG_SCENE_INDICES) readonly buffer IndexBlock { uint indices[]; };
layout(std430, binding = LUCENT_BINDING_LG_CORNERS) readonly buffer CornerBlock { uvec4 corners[]; };
layout(std430, binding = LUCENT_BINDING_LG_VERTEX_RADIOSITY) readonly buffer Radiosity { vec4 vertex_radiosity[]; };

out AtlasViewData {
  vec2 uv;
  vec3 radiosity;
  flat float object_id;
} v_out;

void main() {
  uint k = uint(method.counts.w) + uint(gl_VertexID);
  VertexGPU vertex = vertices[indices[k]];
  uvec4 corner = corners[k];
  v_out.uv = uintBitsToFloat(corner.xy);
  v_out.radiosity = vertex_radiosity[corner.z].rgb;
  v_out.object_id = vertex.position.w + 1.0f;
  gl_Position = frame.clip_from_world * vec4(vertex.position.xyz, 1.0f);
}
