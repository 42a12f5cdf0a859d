// layered_stm_io.h: the layered-stm method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD), the
// per-vertex planes, and its binding points, inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_LAYERED_STM_IO_H
#define LUCENT_METHODS_LAYERED_STM_IO_H
#include "shared/shader_io.h"

#define LUCENT_TEX_LSTM_MAPS 8           // RGBA32F, repeating: thickness of layers 0-3 as fractions of the depth
#define LUCENT_TEX_LSTM_SURFACE 9        // RGBA32F per camera pixel: xy texture coordinates, z object index + 1
#define LUCENT_TEX_LSTM_GRADIENT_U 10    // RGBA32F: xyz the surface gradient of u [1/scene unit]
#define LUCENT_TEX_LSTM_GRADIENT_V 11    // RGBA32F: xyz the surface gradient of v
#define LUCENT_TEX_LSTM_PLANE_NORMAL 12  // RGBA32F: xyz the interpolated least-squares plane's normal
#define LUCENT_TEX_LSTM_PLANE_POINT 13   // RGBA32F: xyz a point of that plane [scene units]
#define LUCENT_IMAGE_LSTM_SUM 2          // RGBA32F: rgb the sum of the estimates over the frames, a their count
#define LUCENT_BINDING_LSTM_VERTICES 20  // VertexGPU[] (std430): the scene's vertex buffer, read by the plane fit
#define LUCENT_BINDING_LSTM_FIT 21       // uvec2[] (std430): per fitted vertex: x vertex index, y first neighbour
#define LUCENT_BINDING_LSTM_NEIGHBOURS 22  // uint[] (std430): neighbour vertex indices, one run per fitted vertex
#define LUCENT_BINDING_LSTM_PLANES 23    // LstmPlaneGPU[] (std430) per scene vertex

LUCENT_SHADER_BEGIN

struct LayeredStmGPU {
  ivec4 counts;     // x: ray-march samples; y: layers (0: one layer of each object's material); z: jitter; w: fitted vertices
  vec4 stack;       // x: depth [scene units]; y: texture tiling; zw: unused
  vec4 sigma_s[4];  // per layer: rgb scattering [1/scene unit]; w: unused
  vec4 sigma_t[4];  // per layer: rgb extinction [1/scene unit]; w: unused
  vec4 k[4];        // per layer: rgb Schlick k; w: unused
};

// A plane fitted around one vertex (std430, 32 bytes).
struct LstmPlaneGPU {
  vec4 normal;  // xyz unit normal, oriented like the vertex normal
  vec4 point;   // xyz the neighbours' centroid [scene units]
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::LayeredStmGPU) == 224);
static_assert(sizeof(lucent::shader::LstmPlaneGPU) == 32);
static_assert(LUCENT_TEX_LSTM_MAPS >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_LSTM_PLANE_POINT <= LUCENT_METHOD_TEX_LAST);
static_assert(LUCENT_IMAGE_LSTM_SUM >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_LSTM_SUM <= LUCENT_METHOD_IMAGE_LAST);
static_assert(LUCENT_BINDING_LSTM_VERTICES >= LUCENT_METHOD_STORAGE_FIRST &&
              LUCENT_BINDING_LSTM_PLANES <= LUCENT_METHOD_STORAGE_LAST);
#endif

#endif
