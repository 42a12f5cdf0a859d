// layered_views.geom: layered rendering of one triangle into every orthographic view of a set (the
// directional lights' G-buffers, or the K scattered-radiosity map views) in a single pass.
// 32 invocations x 2 views each cover LUCENT_MAX_MAPS = 64 layers.
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

uniform int u_view_set;  // 0: lights, 1: radiosity maps

void main() {
  int count = u_view_set == 0 ? frame.counts.x : frame.counts.y;
  for (int k = gl_InvocationID; k < count; k += 32) {
    mat4 clip_from_world = u_view_set == 0 ? frame.lights[k].clip_from_world : frame.maps[k].clip_from_world;
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
