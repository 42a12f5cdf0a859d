// medium_volume.h: heterogeneous media from a file: a raw grid of density multipliers with a small JSON header.
//
//   {                                  the header (e.g. inclusion.json); unknown keys are errors
//     "size": [nx, ny, nz],            voxels per axis, each in [1, 1024], at most 2^27 in all
//     "format": "float32" | "uint8",   little-endian 32-bit floats (m directly) or bytes
//     "range": [lo, hi],               uint8 only: byte 0 maps to m = lo, 255 to m = hi (default [0, 1])
//     "data": "inclusion.raw"          the values, x fastest, then y, then z; relative to the header
//   }
//
// m >= 0 multiplies the material's density (lucent/material.h, MediumField); the grid spans the object's
// world-space bounds. Bad input (missing file, wrong byte count, NaN or negative value, bad key) throws
// lucent::Error naming the file and the problem.
#pragma once
#include <memory>
#include <string>

#include "lucent/material.h"

namespace lucent {

std::shared_ptr<const MediumVolume> load_medium_volume(const std::string& header_path);
// Writes `volume` as float32 next to the header (data file: the header's stem + ".raw").
void save_medium_volume(const MediumVolume& volume, const std::string& header_path);

}  // namespace lucent
