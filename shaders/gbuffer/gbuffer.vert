// gbuffer.vert: world-space vertices (position.w = object index) pass through to the G-buffer fragment stage.
// CAMERA_VIEW: through the frame's camera. LAYERED_VIEWS: instance i through the view i of the pass's layer views
// into layer i (gpu/layer_views.h); one instanced draw fills every layer.
#if defined(LAYERED_VIEWS)
#extension GL_ARB_shader_viewport_layer_array : require
#endif
#include "common/frame.glsl"

layout(location = 0) in vec4 in_position;  // xyz world [scene units], w: object index
layout(location = 1) in vec4 in_normal;    // xyz world unit normal
layout(location = 2) in vec4 in_uv;        // xy: texture coordinates (0 where the mesh has none); zw: those of the
                                           // material's maps (render/scene_gpu.cpp)

#if defined(LAYERED_VIEWS)
layout(std430, binding = LUCENT_BINDING_LAYER_VIEWS) readonly buffer LayerViewBlock { ViewGPU layer_views[]; };
#endif

out VertexData {
  vec3 position;
  vec3 normal;
  vec2 uv;
  flat float object_id;  // object index + 1 (0 marks an empty texel)
} v_out;

void main() {
  v_out.position = in_position.xyz;
  v_out.normal = in_normal.xyz;
  v_out.uv = in_uv.zw;
  v_out.object_id = in_position.w + 1.0f;
#if defined(CAMERA_VIEW)
  gl_Position = frame.clip_from_world * vec4(in_position.xyz, 1.0f);
#elif defined(LAYERED_VIEWS)
  gl_Layer = gl_InstanceID;
  gl_Position = layer_views[gl_InstanceID].clip_from_world * vec4(in_position.xyz, 1.0f);
#else
#error "gbuffer.vert: define CAMERA_VIEW or LAYERED_VIEWS"
#endif
}
