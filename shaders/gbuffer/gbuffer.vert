// gbuffer.vert: world-space vertices (position.w = object index) pass through to the G-buffer stages.
#include "common/frame.glsl"

layout(location = 0) in vec4 in_position;  // xyz world [scene units], w: object index
layout(location = 1) in vec4 in_normal;    // xyz world unit normal
layout(location = 2) in vec4 in_uv;        // xy: texture coordinates (0 where the mesh has none); not used yet

out VertexData {
  vec3 position;
  vec3 normal;
  flat float object_id;  // object index + 1 (0 marks an empty texel)
} v_out;

void main() {
  v_out.position = in_position.xyz;
  v_out.normal = in_normal.xyz;
  v_out.object_id = in_position.w + 1.0f;
#if defined(CAMERA_VIEW)
  gl_Position = frame.clip_from_world * vec4(in_position.xyz, 1.0f);
#else
  gl_Position = vec4(in_position.xyz, 1.0f);
#endif
}
