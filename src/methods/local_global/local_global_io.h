// local_global_io.h: the local-global method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD) and the
// binding points of its passes, inside the method ranges of shared/bindings.h (C++ and GLSL). The precomputed
// tables (local_global_precompute.h) are uploaded as they are, except the vertex texels (two vec4 each).
#ifndef LUCENT_METHODS_LOCAL_GLOBAL_IO_H
#define LUCENT_METHODS_LOCAL_GLOBAL_IO_H
#include "shared/shader_io.h"

#define LUCENT_IMAGE_LG_ILLUMINATION 2        // RGBA32F atlas: F_t E per covered texel (written)
#define LUCENT_IMAGE_LG_LOCAL 3               // RGBA32F atlas: B_l per covered texel (written)
#define LUCENT_TEX_LG_ILLUMINATION 8          // the illumination map (read)
#define LUCENT_TEX_LG_TEXEL_INDEX 9           // R32I atlas: compact texel index, -1 where no texel centre is covered
#define LUCENT_TEX_LG_LOCAL 10                // B_l (read by shade)
#define LUCENT_TEX_LG_VIEW_ATLAS 11           // RGBA32F camera view: xy atlas coordinates, z scene object index + 1
#define LUCENT_TEX_LG_VIEW_RADIOSITY 12       // RGBA32F camera view: rgb B^d + B^g' interpolated over the triangle
#define LUCENT_BINDING_LG_KERNELS 20          // float[texels * 49 * 3] (std430): scatter-form kernels
#define LUCENT_BINDING_LG_CHUNKS 21           // uvec2[] (std430): (first, end) vertex texels of each chunk
#define LUCENT_BINDING_LG_VERTEX_TEXELS 22    // uvec4 pairs (std430): (texel x | y << 16, dual weight bits), (w rgb bits)
#define LUCENT_BINDING_LG_ROW_OFFSETS 23      // uint[vertices + 1] (std430): into the form factors
#define LUCENT_BINDING_LG_FORM_FACTORS 24     // uvec4[] (std430): (source vertex, F' rgb bits) by receiving row
#define LUCENT_BINDING_LG_VERTEX_IRRADIANCE 25  // vec4 pairs per vertex (std430): E^g, B^d
#define LUCENT_BINDING_LG_VERTEX_RADIOSITY 26   // vec4 per vertex (std430): B^d + B^g'
#define LUCENT_BINDING_LG_CORNERS 27          // uvec4 per corner of the scene's index buffer (std430): atlas uv bits, vertex
#define LUCENT_BINDING_LG_SCENE_VERTICES 28   // VertexGPU[] (std430): SceneGpu::vertex_buffer()
#define LUCENT_BINDING_LG_SCENE_INDICES 29    // uint[] (std430): SceneGpu::index_buffer()
// The vertex_irradiance passes reuse two slots of atlas_view's (which binds its own buffers there):
#define LUCENT_BINDING_LG_CHUNK_SUMS 28       // vec4 pairs per chunk (std430): the chunk's part of E^g, B^d; shares slot 28 with LUCENT_BINDING_LG_SCENE_VERTICES
#define LUCENT_BINDING_LG_VERTEX_CHUNKS 29    // uint[vertices + 1] (std430): each vertex's chunks; shares slot 29 with LUCENT_BINDING_LG_SCENE_INDICES

// Mesa's llvmpipe ends an invocation's loops silently after 65,535 iterations in all (kLlvmpipeLoopIterations in
// platform/gl_capabilities.h). A vertex's texels (up to a whole atlas face on a coarse mesh) are therefore summed
// in chunks of at most this many texels, one invocation each, and the chunks' sums per vertex by a second
// dispatch: no invocation of the pass loops more than this many times (checked on the CPU at upload).
#define LUCENT_LG_VERTEX_CHUNK 16384

LUCENT_SHADER_BEGIN

#define LUCENT_LG_SHOW_COMBINED 0
#define LUCENT_LG_SHOW_LOCAL 1
#define LUCENT_LG_SHOW_GLOBAL 2

struct LocalGlobalGPU {
  ivec4 counts;   // x: atlas size; y: vertices; z: texels; w: first corner of the mesh being drawn (atlas_view)
  ivec4 options;  // x: LUCENT_LG_SHOW_* (the `show` parameter); y: chunks of the vertex texels
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::LocalGlobalGPU) == 32);
static_assert(LUCENT_IMAGE_LG_ILLUMINATION >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_LG_LOCAL <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_TEX_LG_ILLUMINATION >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_LG_VIEW_RADIOSITY <= LUCENT_METHOD_TEX_LAST);
static_assert(LUCENT_BINDING_LG_KERNELS >= LUCENT_METHOD_STORAGE_FIRST &&
              LUCENT_BINDING_LG_SCENE_INDICES <= LUCENT_METHOD_STORAGE_LAST);
#endif

#endif
