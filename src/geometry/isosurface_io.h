// isosurface_io.h: the CPU-GPU data contracts of the GPU isosurface extractor (geometry/blob_isosurface.cpp,
// shaders/geometry/): binding points and block layouts, checked by static_assert in C++.
// The binding points lie in the isosurface ranges of shared/bindings.h, apart from the frame's and the methods',
// so an extraction between the renderer's binds and draws disturbs nothing.
#ifndef LUCENT_GEOMETRY_ISOSURFACE_IO_H
#define LUCENT_GEOMETRY_ISOSURFACE_IO_H
#include "shared/bridge.h"
#include "geometry/blob_field.h"
#include "shared/bindings.h"

#define LUCENT_BINDING_ISO_PARAMS 8     // uniform IsosurfaceParamsGPU (std140)
#define LUCENT_BINDING_ISO_SAMPLES 9    // buffer float[] per grid point: the stored field sample (std430)
#define LUCENT_BINDING_ISO_MASKS 10     // buffer uint[] per grid point: bits 0-6 its crossing edges, bits 8-15
                                        // its cell's inside corners (cells' lower corners only) (std430)
#define LUCENT_BINDING_ISO_OFFSETS 11   // buffer uvec2[] per grid point: counts (x vertices, y triangles),
                                        // then, after the scan, the first vertex and first triangle (std430)
#define LUCENT_BINDING_ISO_VERTICES 12  // buffer VertexGPU[] (std430)
#define LUCENT_BINDING_ISO_INDICES 13   // buffer uint[], 3 per triangle (std430)
#define LUCENT_BINDING_ISO_COUNTS 14    // buffer IsosurfaceCountsGPU (std430)
#define LUCENT_BINDING_ISO_DRAW 15      // buffer DrawElementsIndirectGPU (std430), also GL_DRAW_INDIRECT_BUFFER
#define LUCENT_BINDING_ISO_ACTIVE 16    // buffer uint[]: grid points with a vertex or a triangle (std430)
#define LUCENT_BINDING_ISO_DISPATCH 17  // buffer IsosurfaceDispatchGPU (std430), also GL_DISPATCH_INDIRECT_BUFFER
#define LUCENT_BINDING_SCAN_DATA 18     // scan passes: buffer uvec2[] scanned in place (std430)
#define LUCENT_BINDING_SCAN_SUMS 19     // scan passes: buffer uvec2[] one total per block (std430)
#define LUCENT_ISO_MAX_BINDING 19       // the extractor checks GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS against it
#if LUCENT_BINDING_ISO_SAMPLES < LUCENT_ISOSURFACE_STORAGE_FIRST || LUCENT_BINDING_SCAN_SUMS > LUCENT_ISOSURFACE_STORAGE_LAST || \
    LUCENT_BINDING_ISO_PARAMS < LUCENT_ISOSURFACE_UNIFORM_FIRST || LUCENT_BINDING_ISO_PARAMS > LUCENT_ISOSURFACE_UNIFORM_LAST
#error isosurface binding points outside their ranges in shared/bindings.h
#endif

#define LUCENT_ISO_EMIT_GROUP 64  // invocations per workgroup of the emit pass (one per active point)
#define LUCENT_SCAN_BLOCK 1024  // elements per scan workgroup: 256 invocations x 4

LUCENT_SHADER_BEGIN

// Per extraction (std140, 128 bytes).
struct IsosurfaceParamsGPU {
  vec4 lower;       // xyz: grid box lower corner [scene units]; w: time [s]
  vec4 spacing;     // xyz: cell size [scene units]; w: object index, written to VertexGPU.position.w
  ivec4 cells;      // xyz: cells per axis; w: unused
  uvec4 limits;     // x: capacity in triangles (also the vertex capacity); y: capacity of the active list
  BlobState field;  // the blobs at this time (blob_state, evaluated once on the CPU)
};

// The emit pass's indirect dispatch (std430, 16 bytes).
struct IsosurfaceDispatchGPU {
  uint groups_x, groups_y, groups_z;  // glDispatchComputeIndirect arguments
  uint active_points;                 // appended by the classify pass; reset to 0 before it
};

// Written by the GPU each extraction (std430, 16 bytes).
struct IsosurfaceCountsGPU {
  uvec4 totals;  // x: vertices, y: triangles (what the surface needs, even beyond capacity); z: 1 when over
                 // capacity (nothing is drawn then); w: unused
};

// glDrawElementsIndirect's command (std430, 20 bytes).
struct DrawElementsIndirectGPU {
  uint count;  // indices: 3 x triangles
  uint instance_count;
  uint first_index;
  int base_vertex;
  uint base_instance;
};

LUCENT_SHADER_END

#if defined(__cplusplus)
static_assert(sizeof(lucent::shader::IsosurfaceParamsGPU) == 128);
static_assert(sizeof(lucent::shader::IsosurfaceDispatchGPU) == 16);
static_assert(sizeof(lucent::shader::IsosurfaceCountsGPU) == 16);
static_assert(sizeof(lucent::shader::DrawElementsIndirectGPU) == 20);
#endif

#endif
