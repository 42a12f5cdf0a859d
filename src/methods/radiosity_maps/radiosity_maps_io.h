// radiosity_maps_io.h: the radiosity-maps method's own GPU data: its uniform block (at LUCENT_BINDING_METHOD)
// and its binding points, inside the method ranges of shared/bindings.h (C++ and GLSL).
#ifndef LUCENT_METHODS_RADIOSITY_MAPS_IO_H
#define LUCENT_METHODS_RADIOSITY_MAPS_IO_H
#include "shared/shader_io.h"

#define LUCENT_MAX_MAPS 64

#define LUCENT_BINDING_VPLS 20    // buffer VplGPU[] (std430)
#define LUCENT_BINDING_PROBES 21  // buffer ProbeGPU[] (std430), diagnostics
#define LUCENT_TEX_MAP_POSITION 8
#define LUCENT_TEX_MAP_NORMAL 9
#define LUCENT_TEX_MAP_DEPTH 10
#define LUCENT_TEX_RADIOSITY 11
#define LUCENT_TEX_VPL_POSITION 12
#define LUCENT_TEX_VPL_NORMAL 13
#define LUCENT_TEX_VPL_DEPTH 14
#define LUCENT_TEX_MAP_UV 15  // the maps' texture coordinates (scenes with textured materials)
#define LUCENT_IMAGE_RADIOSITY 2

// Debug views of the combine pass (RadiosityMapsGPU.counts.w).
#define LUCENT_VIEW_SHADED 0
#define LUCENT_VIEW_COVERAGE 1

LUCENT_SHADER_BEGIN

// Everything the method's passes read besides the common frame block (std140).
struct RadiosityMapsGPU {
  ivec4 counts;      // x: maps K, y: samples N per band, z: map size [texels], w: debug view (LUCENT_VIEW_*)
  vec4 biases;       // x: eps_bias [map texels], y: eps_comb [map texels], z: filter lod; w: unused
  ivec4 vpls;        // x: VPLs N_vpl (0: off), y: VPL cube-map size [texels], z: visibility taps per axis; w: unused
  vec4 vpl_center;   // xyz: centre of the VPL cube map [scene units]; w: unused
  ViewGPU maps[LUCENT_MAX_MAPS];  // step 2: the scattered-radiosity map views
  ViewGPU vpl_views[6];           // cube map of the translucent objects' outermost surface
};

LUCENT_SHADER_END

#if defined(__cplusplus)
#include <cstddef>
static_assert(offsetof(lucent::shader::RadiosityMapsGPU, maps) == 64);
static_assert(sizeof(lucent::shader::RadiosityMapsGPU) == 64 + 96 * (LUCENT_MAX_MAPS + 6));
static_assert(sizeof(lucent::shader::RadiosityMapsGPU) <= 16384, "GL guarantees uniform blocks of 16 KiB only");
static_assert(LUCENT_BINDING_VPLS >= LUCENT_METHOD_STORAGE_FIRST && LUCENT_BINDING_PROBES <= LUCENT_METHOD_STORAGE_LAST);
static_assert(LUCENT_TEX_MAP_POSITION >= LUCENT_METHOD_TEX_FIRST && LUCENT_TEX_MAP_UV <= LUCENT_METHOD_TEX_LAST);
static_assert(LUCENT_IMAGE_RADIOSITY >= LUCENT_METHOD_IMAGE_FIRST && LUCENT_IMAGE_RADIOSITY <= LUCENT_METHOD_IMAGE_LAST);
#endif

#endif
