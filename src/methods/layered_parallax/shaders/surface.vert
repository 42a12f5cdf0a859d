// surface.vert: world-space vertices through the frame's camera, with their texture coordinates.
#include "common/frame.glsl"

layout(location = 0) in vec4 in_position;  // xyz world [scene units], w: object index
layout(location = 1) in vec4 in_normal;    // xyz world unit normal
layout(location = 2) in vec4 in_uv;        // xy: texture coordinates

out VertexData {
  vec3 position;
  vec3 normal;
  vec2 uv;
  flat float object_id;
} v_out;

void main() {
  v_out.position = in_position.xyz;
  v_out.normal = in_normal.xyz;
  v_out.uv = in_uv.xy;
  v_out.object_id = in_position.w + 1.0f;
  gl_Position = frame.clip_from_world * vec4(in_position.xyz, 1.0f);
}
