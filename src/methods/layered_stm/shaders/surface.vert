// surface.vert: world-space vertices through the frame's camera, with their texture coordinates and the
// least-squares plane fitted around each (planes.comp; zero for vertices without one).
#include "common/frame.glsl"
#include "methods/layered_stm/layered_stm_io.h"

layout(location = 0) in vec4 in_position;  // xyz world [scene units], w: object index
layout(location = 1) in vec4 in_normal;    // xyz world unit normal
layout(location = 2) in vec4 in_uv;        // xy: texture coordinates

layout(std430, binding = LUCENT_BINDING_LSTM_PLANES) readonly buffer PlaneBlock { LstmPlaneGPU planes[]; };

out VertexData {
  vec3 position;
  vec3 normal;
  vec2 uv;
  vec3 plane_normal;
  vec3 plane_point;
  flat float object_id;
} v_out;

void main() {
  v_out.position = in_position.xyz;
  v_out.normal = in_normal.xyz;
  v_out.uv = in_uv.xy;
  LstmPlaneGPU plane = planes[gl_VertexID];
  v_out.plane_normal = plane.normal.xyz;
  v_out.plane_point = plane.point.w > 0.5f ? plane.point.xyz : in_position.xyz;
  v_out.object_id = in_position.w + 1.0f;
  gl_Position = frame.clip_from_world * vec4(in_position.xyz, 1.0f);
}
