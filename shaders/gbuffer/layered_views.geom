// layered_views.geom: layered rendering of one triangle into every view of a set (the light G-buffer layers:
// orthographic for directional lights, perspective frusta and cube faces for point lights; or the K
// scattered-radiosity map views) in a single pass.
// 32 invocations x 2 views each cover LUCENT_MAX_MAPS = LUCENT_MAX_LIGHT_VIEWS = 64 layers.
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

uniform int u_view_set;  // 0: the light G-buffer layers (frame.light_views), 1: the maps, 2: the VPL cube

mat4 view_matrix(int k) {
  if (u_view_set == 2) return frame.vpl_views[k].clip_from_world;
  return u_view_set == 1 ? frame.maps[k].clip_from_world : frame.light_views[k].clip_from_world;
}

void main() {
  int count = u_view_set == 0 ? frame.extra_counts.x : u_view_set == 1 ? frame.counts.y : 6;
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
