// medium_vdb.h: heterogeneous media from OpenVDB files: one float grid, times a factor, resampled into the dense
// MediumVolume that the raw volume files give (lucent/medium_volume.h), so voxel-paths and volpath use it unchanged.
//
//   "field": { "type": "vdb", "file": "smoke.vdb", "grid": "density", "density_scale": 1.0,
//              "transform": "object-bounds" | "vdb-world" }
//
// m(x) = density_scale * grid value (trilinear between voxel centres, as OpenVDB's BoxSampler).
//   object-bounds  (default) the grid's active index bounding box, one dense voxel per VDB voxel (the values copied,
//                  no interpolation), spans the object's world-space bounds like a raw volume file; the VDB's own
//                  transform is ignored. Outside the box the border values continue (clamped).
//   vdb-world      the VDB's world coordinates are the scene's world coordinates (scene units), fixed in the scene
//                  whatever the object's transform. The dense grid covers the world-space box of the active voxels
//                  plus one voxel of background on each side (so m is the background outside), at the VDB's voxel
//                  size: n = round(extent / voxel size) per axis; for an axis-aligned transform its centres are the
//                  VDB's voxel centres and the values are copied, otherwise BoxSampler resamples them. Linear
//                  transforms only (no frustum).
// Limits, as for raw volumes: at most 1024 voxels per axis and 2^27 in all after resampling. Bad input throws
// lucent::Error naming the file: missing, not a VDB file, a header or grid that runs past the end of the file
// (checked before OpenVDB reads it), no grid of that name (the grids present are listed), a grid that is not
// float, no active voxels, a negative or NaN value, a size over the limits. OpenVDB reads the file in a child
// process (src/scene/import_guard.h) under CPU, wall-clock and memory limits, so a file that makes it crash or
// allocate without bound is an error too ("cannot read the VDB file: the OpenVDB reader ran out of memory (limit
// 4352 MiB)" with 2 hardware threads); text OpenVDB quotes from the file shows its unprintable bytes as \xNN.
//
// OpenVDB (with its oneTBB and Boost headers) is compiled into one file, src/media/medium_vdb.cpp, in its own
// library lucent_vdb; this header declares no OpenVDB type (docs/design.md, "Libraries").
#pragma once
#include <memory>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "lucent/material.h"

namespace lucent {

std::string_view to_string(VdbTransform transform);  // "object-bounds", "vdb-world"

struct VdbVolume {
  std::shared_ptr<const MediumVolume> volume;  // the resampled grid (source and data_file: the .vdb file)
  bool world = false;                          // vdb-world: the volume spans [lower, upper] in scene units
  glm::vec3 lower{0.0f}, upper{0.0f};
};

VdbVolume load_medium_vdb(const VdbField& field);

// The field a volume was read from (MediumVolume::vdb), so a saved scene names the VDB file, grid and factor again
// (src/scene/scene_writer.cpp); nullptr for a volume from a raw file.
inline const VdbField* vdb_field_of(const std::shared_ptr<const MediumVolume>& volume) {
  return volume && volume->vdb ? &*volume->vdb : nullptr;
}

}  // namespace lucent
