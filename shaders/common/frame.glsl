// frame.glsl: the frame's uniform block and the scene's material and object buffers (layouts in
// shared/shader_io.h).
#include "shared/shader_io.h"

layout(std140, binding = LUCENT_BINDING_FRAME) uniform FrameBlock { FrameGPU frame; };
layout(std430, binding = LUCENT_BINDING_MATERIALS) readonly buffer MaterialBlock { MaterialGPU materials[]; };
layout(std430, binding = LUCENT_BINDING_OBJECTS) readonly buffer ObjectBlock { ObjectGPU objects[]; };

// Texture coordinates (u, v, depth in [0, 1]) of a world point in an orthographic view.
vec3 view_texture_coords(mat4 clip_from_world, vec3 x) {
  return 0.5f * (clip_from_world * vec4(x, 1.0f)).xyz + vec3(0.5f);
}
