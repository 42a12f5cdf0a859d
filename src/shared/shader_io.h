// shader_io.h: every CPU-GPU data contract, declared once: binding points, uniform and storage block
// layouts (std140 / std430, vec4-aligned, no implicit padding), with size and offset checks for C++.
#ifndef LUCENT_SHARED_SHADER_IO_H
#define LUCENT_SHARED_SHADER_IO_H
#include "shared/bridge.h"

#include "shared/bindings.h"

#define LUCENT_MAX_LIGHTS 16       // directional, point and spot lights together
#define LUCENT_MAX_LIGHT_VIEWS 64  // light G-buffer layers (directional: 2, point and spot: 6 or 7)
#define LUCENT_MAX_LAYERS 64       // views one layered G-buffer pass renders (gpu/layer_views.h)

// FrameGPU.environment.x bits.
#define LUCENT_ENVIRONMENT_MAP 1         // an environment map is bound at LUCENT_TEX_ENVIRONMENT
#define LUCENT_ENVIRONMENT_BACKGROUND 2  // camera rays that miss see it

// Light types (LightGPU.position.w).
#define LUCENT_LIGHT_DIRECTIONAL 0
#define LUCENT_LIGHT_POINT 1
#define LUCENT_LIGHT_SPOT 2

LUCENT_SHADER_BEGIN

// One translucent material, coefficients already converted to scene units (std430, 80 bytes).
struct MaterialGPU {
  vec4 sigma_a;     // xyz: absorption [1/scene unit]; w: eta (relative refractive index)
  vec4 sigma_s;     // xyz: scattering, unreduced [1/scene unit]; w: BSSRDF model id (LUCENT_MODEL_*)
  vec4 g;           // xyz: Henyey-Greenstein g per band; w: the multipole model's slab thickness [scene units]
  ivec4 alpha_map;  // a textured material's maps (media/material_map.h): x the first texel in the material-map
  ivec4 mfp_map;    // buffer (-1: none), y and z width and height; w unused. sigma_a and sigma_s are the maps' mean.
};

// One scene object (std430, 32 bytes).
struct ObjectGPU {
  vec4 albedo;  // rgb: diffuse albedo of an opaque object; a: unused
  ivec4 info;   // x: material index, -1 for an opaque object; y: first texel of its thickness grid in the material
                // map buffer, -1 for none (geometry/thickness_field.h); zw: unused
};

// One view of a light G-buffer layer or of a scattered-radiosity map (std140, 96 bytes). Orthographic views
// (directional lights, maps) or perspective ones (the faces of a point light's cube map, or one frustum framing
// the translucent objects); texture coordinates are 0.5 * clip / clip.w + 0.5.
struct ViewGPU {
  mat4 clip_from_world;
  vec4 direction;        // orthographic: xyz unit direction (light: the way it travels; map: from the object
                         // toward the map's camera, d_k); w: width of the square view [scene units]
  vec4 radiance;         // w: orthographic: depth range [scene units]; perspective: texel angle [radians]
};

// One light (std140, 64 bytes). Irradiance on a surface facing it: directional `power.rgb`; point and spot
// `power.rgb / d^2` with d in scene units (the CPU folds scale_mm into power).
struct LightGPU {
  vec4 position;  // xyz: position [scene units] (point, spot) or unit direction travelled (directional);
                  // w: type (LUCENT_LIGHT_*)
  vec4 power;     // rgb: irradiance (directional) or intensity per scene unit^2 (point, spot); w: cos inner cone
  vec4 axis;      // spot: xyz unit direction travelled along the axis, w: cos outer cone;
                  // directional: w = 1 with a GGX highlight, 0 without (environment lights)
  ivec4 views;    // x: first light-G-buffer layer framing the translucent objects, y: its layer count (1 view,
                  // or 6 cube faces +X -X +Y -Y +Z -Z), z: first layer of the scene-wide shadow view(s), w: count
};

// One vertex of the world-space scene vertex buffer (48 bytes).
struct VertexGPU {
  vec4 position;  // xyz world [scene units]; w: object index
  vec4 normal;    // xyz world unit normal; w: unused
  vec4 uv;        // xy: texture coordinates (0 where the mesh has none); zw: those of a textured material's maps
                  // (TriangleMesh::map_uvs: the same, or the mesh's own under an atlas)
};

// What every pass of a frame may read, whatever the method (std140). A method's own per-frame data lives in
// its own block at LUCENT_BINDING_METHOD, declared in its folder.
struct FrameGPU {
  mat4 clip_from_world;  // camera
  vec4 camera_position;  // xyz [scene units]
  vec4 background;       // rgb radiance
  ivec4 output_size;     // x: width, y: height [pixels]; zw: unused
  uvec4 seeds;           // x: user seed (low 32 bits), y: frame counter (never repeats), z: 1 = restart
                         // accumulation, w: the user seed's high 32 bits
  vec4 display;          // x: exposure scale 2^stops, y: tone-map operator; zw: unused
  vec4 shading;          // x: 1 = GGX specular reflection of the lights, y: its roughness (GGX alpha); zw: unused
  ivec4 light_counts;    // x: lights, y: light G-buffer layers, z: light-map size [texels], w: shadow taps per axis
  ivec4 environment;     // x: flags (LUCENT_ENVIRONMENT_*); yzw: unused
  LightGPU lights[LUCENT_MAX_LIGHTS];
  ViewGPU light_views[LUCENT_MAX_LIGHT_VIEWS];  // the light G-buffer layers (shadows and light-space sampling)
};

// Per-frame counters written by the passes with atomics (std430, 16 bytes), zeroed by the renderer each frame
// and read back a few frames later (gpu/frame_profiler.h).
struct CountersGPU {
  uint translucent_pixels;  // camera pixels on translucent objects
  uint covered_pixels;      // of those, the ones the method has radiance for
  uint method_counts[2];    // the method's own (its statistics() gives their meaning)
};

// A virtual point light on a translucent object's outer surface (Dal Corso et al. 2015, Section 3.4; std430).
// It emits L(w) = F_t(w) B / pi over its area, so its intensity toward w is F_t(w) B A cos(theta) / pi (eq. 16).
struct VplGPU {
  vec4 position;   // xyz [scene units]; w: surface area A_v it stands for [scene units^2], 0 when inactive
  vec4 normal;     // xyz: outward unit normal; w: eta of its material
  vec4 radiosity;  // rgb: scattered radiosity B(x_v) from the maps (Algorithm 1); w: unused
};

// A point where a diagnostic asks for the scattered radiosity from the maps (std430).
struct ProbeGPU {
  vec4 position;   // xyz [scene units]; w: object index
  vec4 normal;     // xyz: unit normal
  vec4 radiosity;  // out: rgb B(x) (Algorithm 1), w: 1 when a map sees x, else 0
};

// One configuration of the GPU parity test (std430, 144 bytes), in one read-write buffer at
// LUCENT_BINDING_PARITY: shaders/tests/bssrdf_parity.comp evaluates the shared BSSRDF code for it and writes
// `result`; the C++ test evaluates the same code and compares.
struct ParityResultGPU {
  vec4 S_d;  // rgb: S_d [mm^-2]; w: T12(w_i)
};
struct ParityCaseGPU {
  vec4 x_i, w_i, n_i, x_o, n_o;  // xyz used [mm]
  vec4 sigma_a;                  // xyz [mm^-1]; w: eta
  vec4 sigma_s;                  // xyz [mm^-1]; w: model id
  vec4 g;                        // xyz
  ParityResultGPU result;        // written by the shader
};

LUCENT_SHADER_END

#if defined(__cplusplus)
#include <cstddef>
static_assert(sizeof(lucent::shader::MaterialGPU) == 80);
static_assert(sizeof(lucent::shader::ObjectGPU) == 32);
static_assert(sizeof(lucent::shader::ViewGPU) == 96);
static_assert(sizeof(lucent::shader::VertexGPU) == 48);
static_assert(sizeof(lucent::shader::ParityCaseGPU) == 144);
static_assert(offsetof(lucent::shader::FrameGPU, output_size) == 96);
static_assert(sizeof(lucent::shader::LightGPU) == 64);
static_assert(sizeof(lucent::shader::VplGPU) == 48);
static_assert(sizeof(lucent::shader::CountersGPU) == 16);
static_assert(sizeof(lucent::shader::ProbeGPU) == 48);
static_assert(offsetof(lucent::shader::FrameGPU, environment) == 176);
static_assert(offsetof(lucent::shader::FrameGPU, lights) == 192);
static_assert(offsetof(lucent::shader::FrameGPU, light_views) == 192 + 64 * LUCENT_MAX_LIGHTS);
static_assert(sizeof(lucent::shader::FrameGPU) == 192 + 64 * LUCENT_MAX_LIGHTS + 96 * LUCENT_MAX_LIGHT_VIEWS);
static_assert(sizeof(lucent::shader::FrameGPU) <= 16384, "GL guarantees uniform blocks of 16 KiB only");
#endif

#endif
