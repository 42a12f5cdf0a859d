// layered_views.geom: layered rendering of one triangle into every view of a set (the light G-buffer layers:
// orthographic for directional lights, perspective frusta and cube faces for point lights; or the K
// scattered-radiosity map views) in a single pass.
// 32 invocations x 2 views each cover LUCENT_MAX_LAYERS = 64 layers.
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

// The views of the pass being drawn, bound by it (gpu/layer_views.h).
layout(std430, binding = LUCENT_BINDING_LAYER_VIEWS) readonly buffer LayerViewBlock { ViewGPU layer_views[]; };

void main() {
  int count = min(layer_views.length(), LUCENT_MAX_LAYERS);
  for (int k = gl_InvocationID; k < count; k += 32) {
    mat4 clip_from_world = layer_views[k].clip_from_world;
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
