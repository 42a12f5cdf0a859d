// medium_vdb.cpp: the OpenVDB reader of media/medium_vdb_reader.h (lucent/medium_vdb.h). The only file that
// includes OpenVDB (library lucent_vdb).
#include "media/medium_vdb_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include "io/printable_text.h"
#include "lucent/error.h"

namespace lucent {
namespace {

constexpr long long kMaxAxis = 1024;                       // as raw volume files (lucent/medium_volume.h)
constexpr long long kMaxVoxels = 1LL << 27;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(fmt::format("{}: {}", path, problem));
}

void initialize_openvdb() {
  static const bool initialized = [] {
    openvdb::initialize();
    return true;
  }();
  (void)initialized;
}

std::string grid_names(openvdb::io::File& file) {
  std::string names;
  for (auto it = file.beginName(); it != file.endName(); ++it) names += (names.empty() ? "" : ", ") + *it;
  return names.empty() ? "none" : printable_text(names);
}

openvdb::FloatGrid::Ptr read_float_grid(const VdbField& field) {
  const std::string& path = field.file;
  initialize_openvdb();
  openvdb::GridBase::Ptr base;
  try {
    openvdb::io::File file(path);
    file.open(false);
    if (!file.hasGrid(field.grid))
      fail(path, fmt::format("no grid '{}' (grids: {})", printable_text(field.grid), grid_names(file)));
    base = file.readGrid(field.grid);
    file.close();
  } catch (const openvdb::Exception& e) {
    fail(path, fmt::format("cannot read the VDB file ({})", printable_text(e.what())));
  }
  if (!base->isType<openvdb::FloatGrid>())
    fail(path, fmt::format("grid '{}' holds {} values; a vdb field needs a float grid", printable_text(field.grid),
                           printable_text(base->valueType())));
  openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  if (grid->activeVoxelCount() == 0)
    fail(path, fmt::format("grid '{}' has no active voxels", printable_text(field.grid)));
  auto check = [&](float v, const std::string& where) {
    if (!std::isfinite(v) || v < 0.0f)
      fail(path, fmt::format("grid '{}': value {} at {} is not a finite m >= 0", printable_text(field.grid), v, where));
  };
  check(grid->background(), "the background");
  for (auto it = grid->cbeginValueAll(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    check(*it, fmt::format("[{}, {}, {}]", c.x(), c.y(), c.z()));
  }
  return grid;
}

// Rejects a dense size over the limits (before anything is allocated).
glm::ivec3 checked_size(const std::array<long long, 3>& n, const VdbField& field, const char* what) {
  const bool over = std::any_of(n.begin(), n.end(), [](long long a) { return a > kMaxAxis; }) ||
                    n[0] * n[1] * n[2] > kMaxVoxels;  // each factor <= kMaxAxis here
  if (over)
    fail(field.file, fmt::format("grid '{}': {} {}x{}x{} voxels is over the limit ({} per axis, 2^27 in all)",
                                 printable_text(field.grid), what, n[0], n[1], n[2], kMaxAxis));
  return {static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2])};
}

}  // namespace

std::string_view to_string(VdbTransform transform) {
  return transform == VdbTransform::VdbWorld ? "vdb-world" : "object-bounds";
}

VdbVolume read_medium_vdb(const VdbField& field) {
  if (!(field.density_scale >= 0.0f) || !std::isfinite(field.density_scale))
    fail(field.file, fmt::format("density_scale {} is not a finite number >= 0", field.density_scale));
  openvdb::FloatGrid::Ptr grid = read_float_grid(field);
  const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
  auto volume = std::make_shared<MediumVolume>();
  volume->vdb = field;
  volume->source = field.file;
  volume->data_file = field.file;
  VdbVolume out;
  const auto accessor = grid->getConstAccessor();
  if (field.transform == VdbTransform::ObjectBounds) {
    const openvdb::Coord dim = box.dim();
    volume->size = checked_size({dim.x(), dim.y(), dim.z()}, field, "active bounding box");
    volume->values.reserve(static_cast<std::size_t>(dim.x()) * static_cast<std::size_t>(dim.y()) *
                           static_cast<std::size_t>(dim.z()));
    for (int z = box.min().z(); z <= box.max().z(); ++z)
      for (int y = box.min().y(); y <= box.max().y(); ++y)
        for (int x = box.min().x(); x <= box.max().x(); ++x)
          volume->values.push_back(field.density_scale * accessor.getValue(openvdb::Coord(x, y, z)));
  } else {
    const openvdb::math::Transform& transform = grid->transform();
    if (!transform.isLinear())
      fail(field.file, fmt::format("grid '{}' has a non-linear (frustum) transform; vdb-world needs a linear one",
                                   printable_text(field.grid)));
    // The active box plus one voxel of background on each side, in index space (voxel centres at integers).
    const openvdb::Vec3d index_lower = box.min().asVec3d() - openvdb::Vec3d(1.5);
    const openvdb::Vec3d index_upper = box.max().asVec3d() + openvdb::Vec3d(1.5);
    openvdb::Vec3d lower(std::numeric_limits<double>::max()), upper(-std::numeric_limits<double>::max());
    for (int corner = 0; corner < 8; ++corner) {
      const openvdb::Vec3d p((corner & 1) ? index_upper.x() : index_lower.x(),
                             (corner & 2) ? index_upper.y() : index_lower.y(),
                             (corner & 4) ? index_upper.z() : index_lower.z());
      const openvdb::Vec3d w = transform.indexToWorld(p);
      lower = openvdb::math::minComponent(lower, w), upper = openvdb::math::maxComponent(upper, w);
    }
    // Spacing along world axis a: the smallest voxel size of the index axes that move along it (for an
    // axis-aligned transform the matching axis's, so the dense centres are the VDB's voxel centres).
    const openvdb::Vec3d origin = transform.indexToWorld(openvdb::Vec3d(0.0));
    std::array<openvdb::Vec3d, 3> axis;
    for (int k = 0; k < 3; ++k) {
      openvdb::Vec3d e(0.0);
      e[k] = 1.0;
      axis[static_cast<std::size_t>(k)] = transform.indexToWorld(e) - origin;
    }
    std::array<long long, 3> n{};
    for (int a = 0; a < 3; ++a) {
      double spacing = std::numeric_limits<double>::max();
      for (const openvdb::Vec3d& column : axis)
        if (std::abs(column[a]) > 1e-6 * column.length()) spacing = std::min(spacing, column.length());
      const double cells = (upper[a] - lower[a]) / spacing;
      n[static_cast<std::size_t>(a)] = cells > 2.0 * kMaxAxis ? 2 * kMaxAxis : std::max(1LL, std::llround(cells));
    }
    volume->size = checked_size(n, field, "resampled to");
    const openvdb::Vec3d step = (upper - lower) / openvdb::Vec3d(static_cast<double>(n[0]),
                                                                 static_cast<double>(n[1]), static_cast<double>(n[2]));
    volume->values.reserve(static_cast<std::size_t>(n[0] * n[1] * n[2]));
    for (long long z = 0; z < n[2]; ++z)
      for (long long y = 0; y < n[1]; ++y)
        for (long long x = 0; x < n[0]; ++x) {
          const openvdb::Vec3d world = lower + step * openvdb::Vec3d(static_cast<double>(x) + 0.5,
                                                                     static_cast<double>(y) + 0.5,
                                                                     static_cast<double>(z) + 0.5);
          const float v = openvdb::tools::BoxSampler::sample(accessor, transform.worldToIndex(world));
          volume->values.push_back(field.density_scale * v);
        }
    out.world = true;
    out.lower = glm::vec3(static_cast<float>(lower.x()), static_cast<float>(lower.y()), static_cast<float>(lower.z()));
    out.upper = glm::vec3(static_cast<float>(upper.x()), static_cast<float>(upper.y()), static_cast<float>(upper.z()));
  }
  volume->max_value = *std::max_element(volume->values.begin(), volume->values.end());
  if (!(volume->max_value <= kMaxDensityMultiplier))
    fail(field.file, fmt::format("grid '{}': values times density_scale {} reach {:g}; a density multiplier is at most "
                                 "{:g}",
                                 printable_text(field.grid), field.density_scale, volume->max_value, kMaxDensityMultiplier));
  out.volume = std::move(volume);
  return out;
}

}  // namespace lucent
