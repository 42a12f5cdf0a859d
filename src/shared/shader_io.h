// shader_io.h: every CPU-GPU data contract, declared once: binding points, uniform and storage block
// layouts (std140 / std430, vec4-aligned, no implicit padding), with size and offset checks for C++.
#ifndef LUCENT_SHARED_SHADER_IO_H
#define LUCENT_SHARED_SHADER_IO_H
#include "shared/bridge.h"

// Buffer binding points.
#define LUCENT_BINDING_FRAME 0       // uniform FrameGPU (std140)
#define LUCENT_BINDING_MATERIALS 1   // buffer MaterialGPU[] (std430)
#define LUCENT_BINDING_OBJECTS 2     // buffer ObjectGPU[] (std430)
#define LUCENT_BINDING_PARITY 3      // buffer used by the GPU parity test (std430)
#define LUCENT_BINDING_COUNTERS 4    // buffer uint[]: x = covered map texels this frame (std430)

// Texture units (samplers) and image units.
#define LUCENT_TEX_CAMERA_POSITION 0
#define LUCENT_TEX_CAMERA_NORMAL 1
#define LUCENT_TEX_LIGHT_POSITION 2
#define LUCENT_TEX_LIGHT_NORMAL 3
#define LUCENT_TEX_LIGHT_DEPTH 4
#define LUCENT_TEX_MAP_POSITION 5
#define LUCENT_TEX_MAP_NORMAL 6
#define LUCENT_TEX_MAP_DEPTH 7
#define LUCENT_TEX_RADIOSITY 8
#define LUCENT_TEX_HDR 9
#define LUCENT_IMAGE_RADIOSITY 0
#define LUCENT_IMAGE_HDR 1
#define LUCENT_IMAGE_LDR 2

#define LUCENT_MAX_LIGHTS 8
#define LUCENT_MAX_MAPS 64

// Debug views written by the combine pass (FrameGPU.options.y).
#define LUCENT_VIEW_SHADED 0
#define LUCENT_VIEW_COVERAGE 1

LUCENT_SHADER_BEGIN

// One translucent material, coefficients already converted to scene units (std430, 48 bytes).
struct MaterialGPU {
  vec4 sigma_a;  // xyz: absorption [1/scene unit]; w: eta (relative refractive index)
  vec4 sigma_s;  // xyz: scattering, unreduced [1/scene unit]; w: BSSRDF model id (LUCENT_MODEL_*)
  vec4 g;        // xyz: Henyey-Greenstein g per band; w: unused
};

// One scene object (std430, 32 bytes).
struct ObjectGPU {
  vec4 albedo;  // rgb: diffuse albedo of an opaque object; a: unused
  ivec4 info;   // x: material index, -1 for an opaque object; yzw: unused
};

// An orthographic view: a directional light's G-buffer or a scattered-radiosity map (std140, 96 bytes).
struct ViewGPU {
  mat4 clip_from_world;  // orthographic; texture coordinates are 0.5 * clip + 0.5
  vec4 direction;        // xyz: unit direction (light: the way it travels; map: from the object toward the
                         // map's camera, d_k); w: width of the square view [scene units]
  vec4 radiance;         // light: rgb radiance, w: depth range [scene units]; map: unused
};

// One vertex of the world-space scene vertex buffer (32 bytes).
struct VertexGPU {
  vec4 position;  // xyz world [scene units]; w: object index
  vec4 normal;    // xyz world unit normal; w: unused
};

// Everything a frame's passes read (std140).
struct FrameGPU {
  mat4 clip_from_world;  // camera
  vec4 camera_position;  // xyz [scene units]
  vec4 background;       // rgb radiance
  ivec4 counts;          // x: lights, y: maps K, z: samples N per band, w: visibility taps per axis
  ivec4 sizes;           // x: map size, y: light-map size, z: output width, w: output height
  uvec4 seeds;           // x: user seed, y: frame counter (never repeats), z: 1 = restart accumulation
  vec4 biases;           // x: eps_bias [map texels], y: eps_comb [map texels], z: filter lod, w: roughness
  vec4 options;          // x: exposure scale 2^stops, y: debug view, z: specular on, w: tone-map operator
  ViewGPU lights[LUCENT_MAX_LIGHTS];   // light G-buffer views framing the translucent objects (step 1)
  ViewGPU shadows[LUCENT_MAX_LIGHTS];  // the same lights framing the whole scene: shadows of opaque objects
  ViewGPU maps[LUCENT_MAX_MAPS];
};

// One configuration of the GPU parity test (std430, 128 bytes): shaders/tests/bssrdf_parity.comp evaluates
// the shared BSSRDF code for it and writes `result`; the C++ test evaluates the same code and compares.
struct ParityCaseGPU {
  vec4 x_i, w_i, n_i, x_o, n_o;  // xyz used [mm]
  vec4 sigma_a;                  // xyz [mm^-1]; w: eta
  vec4 sigma_s;                  // xyz [mm^-1]; w: model id
  vec4 g;                        // xyz
};
struct ParityResultGPU {
  vec4 S_d;  // rgb: S_d [mm^-2]; w: T12(w_i)
};

LUCENT_SHADER_END

#if defined(__cplusplus)
#include <cstddef>
static_assert(sizeof(lucent::shader::MaterialGPU) == 48);
static_assert(sizeof(lucent::shader::ObjectGPU) == 32);
static_assert(sizeof(lucent::shader::ViewGPU) == 96);
static_assert(sizeof(lucent::shader::VertexGPU) == 32);
static_assert(sizeof(lucent::shader::ParityCaseGPU) == 128);
static_assert(offsetof(lucent::shader::FrameGPU, counts) == 96);
static_assert(offsetof(lucent::shader::FrameGPU, lights) == 176);
static_assert(offsetof(lucent::shader::FrameGPU, shadows) == 176 + 96 * LUCENT_MAX_LIGHTS);
static_assert(offsetof(lucent::shader::FrameGPU, maps) == 176 + 96 * 2 * LUCENT_MAX_LIGHTS);
static_assert(sizeof(lucent::shader::FrameGPU) == 176 + 96 * (2 * LUCENT_MAX_LIGHTS + LUCENT_MAX_MAPS));
#endif

#endif
