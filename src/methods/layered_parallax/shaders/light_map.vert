// light_map.vert: a translucent object drawn in its texture space (Oat 2006; Norberg 2010, Section 2.2.2): the
// texture coordinates are the position, the layer is the object's index, so that objects sharing a texture layout
// do not overwrite each other's light.
#extension GL_ARB_shader_viewport_layer_array : require
#include "common/frame.glsl"

layout(location = 0) in vec4 in_position;  // xyz world [scene units], w: object index
layout(location = 1) in vec4 in_normal;    // xyz world unit normal
layout(location = 2) in vec4 in_uv;        // xy: texture coordinates

out VertexData {
  vec3 position;
  vec3 normal;
} v_out;

void main() {
  v_out.position = in_position.xyz;
  v_out.normal = in_normal.xyz;
  gl_Layer = int(in_position.w + 0.5f);
  gl_Position = vec4(2.0f * in_uv.xy - 1.0f, 0.0f, 1.0f);
}
