// gbuffer.vert: the texture-space G-buffer (src/texture_space/texture_gbuffer.h), step 1 of 3. One invocation per
// triangle corner of one translucent mesh, pulled from the scene's world-space vertex and index buffers (so a
// deforming mesh is drawn as it is this frame) with its atlas coordinates (rest pose) from the corner buffer.
#include "shared/shader_io.h"

layout(std430, binding = TEXTURE_SPACE_BINDING_VERTICES) readonly buffer VertexBlock { VertexGPU vertices[]; };
layout(std430, binding = TEXTURE_SPACE_BINDING_INDICES) readonly buffer IndexBlock { uint indices[]; };
layout(std430, binding = TEXTURE_SPACE_BINDING_CORNER_UVS) readonly buffer CornerUvBlock { vec2 corner_uvs[]; };

uniform uint u_first_index;  // the mesh's first corner in indices[]

out CornerData {
  vec3 position;  // world [scene units]
  vec3 normal;    // world, unit
  vec2 uv;        // atlas [0, 1]^2
  float object;   // scene object index
} corner;

void main() {
  uint k = u_first_index + uint(gl_VertexID);
  VertexGPU vertex = vertices[indices[k]];
  corner.position = vertex.position.xyz;
  corner.normal = vertex.normal.xyz;
  corner.object = vertex.position.w;
  corner.uv = corner_uvs[k];
  gl_Position = vec4(corner.uv * 2.0f - 1.0f, 0.0f, 1.0f);
}
