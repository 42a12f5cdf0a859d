// isosurface_draw.vert: the blob isosurface test draw: VertexGPU attributes (0: position, 1: normal),
// orthographic view of the box [-2, 2]^3 along -z.
layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
layout(location = 0) out vec3 v_normal;

void main() {
  gl_Position = vec4(0.5f * position.xyz, 1.0f);
  v_normal = normal.xyz;
}
