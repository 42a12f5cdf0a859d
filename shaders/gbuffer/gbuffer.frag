// gbuffer.frag: writes world position (w: object index + 1), world normal and texture coordinates (kept only by
// G-buffers with a texture-coordinate attachment, gpu/gbuffer.h).
in VertexData {
  vec3 position;
  vec3 normal;
  vec2 uv;
  flat float object_id;
} v_in;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec2 out_uv;

void main() {
  out_position = vec4(v_in.position, v_in.object_id);
  out_normal = vec4(normalize(v_in.normal), 0.0f);
  out_uv = v_in.uv;
}
