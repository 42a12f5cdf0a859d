// gbuffer.frag: writes world position (w: object index + 1) and world normal.
in VertexData {
  vec3 position;
  vec3 normal;
  flat float object_id;
} v_in;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;

void main() {
  out_position = vec4(v_in.position, v_in.object_id);
  out_normal = vec4(normalize(v_in.normal), 0.0f);
}
