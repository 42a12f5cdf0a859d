// layered_views.geom: layered rendering of one triangle into every orthographic view of a set (the
// directional lights' G-buffers, or the K scattered-radiosity map views) in a single pass.
// 32 invocations x 2 views each cover LUCENT_MAX_MAPS = 64 layers (and 2 x LUCENT_MAX_LIGHTS light layers).
#include "common/frame.glsl"

layout(triangles, invocations = 32) in;
layout(triangle_strip, max_vertices = 6) out;

in VertexData {
  vec3 position;
  vec3 normal;
  flat float object_id;
} v_in[];

out VertexData {
  vec3 position;
  vec3 normal;
  flat float object_id;
} v_out;

uniform int u_view_set;  // 0: lights (layers [0, L) object views, [L, 2L) scene-wide shadow views), 1: maps

mat4 view_matrix(int k) {
  if (u_view_set == 1) return frame.maps[k].clip_from_world;
  return k < frame.counts.x ? frame.lights[k].clip_from_world : frame.shadows[k - frame.counts.x].clip_from_world;
}

void main() {
  int count = u_view_set == 0 ? 2 * frame.counts.x : frame.counts.y;
  for (int k = gl_InvocationID; k < count; k += 32) {
    mat4 clip_from_world = view_matrix(k);
    for (int i = 0; i < 3; ++i) {
      gl_Layer = k;
      gl_Position = clip_from_world * vec4(v_in[i].position, 1.0f);
      v_out.position = v_in[i].position;
      v_out.normal = v_in[i].normal;
      v_out.object_id = v_in[i].object_id;
      EmitVertex();
    }
    EndPrimitive();
  }
}
