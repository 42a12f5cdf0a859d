// deformation.cpp: per-frame vertex deformations of SceneObject (scene.h) and scene_at_time().
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

#include "geometry/isosurface_cpu.h"
#include "geometry/isosurface_grid.h"
#include "lucent/scene.h"

namespace lucent {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// The smooth-surface vertex of each vertex: vertices with bitwise-equal rest position and rest normal share one.
// They are copies along a texture seam (or the two rings of a smooth lathe corner), one point of a smooth
// surface; vertices duplicated at creases differ in their normals and stay apart.
std::vector<std::uint32_t> smooth_groups(const TriangleMesh& rest) {
  std::array<std::uint32_t, 6> key{};
  auto key_of = [&](std::size_t i) {
    std::memcpy(key.data(), &rest.positions[i], sizeof(glm::vec3));
    std::memcpy(key.data() + 3, &rest.normals[i], sizeof(glm::vec3));
    return key;
  };
  auto hash = [](const std::array<std::uint32_t, 6>& k) {
    std::size_t h = 0;
    for (std::uint32_t word : k) h = (h ^ word) * 0x100000001b3ull;
    return h;
  };
  std::unordered_map<std::array<std::uint32_t, 6>, std::uint32_t, decltype(hash)> ids(rest.positions.size(), hash);
  std::vector<std::uint32_t> group(rest.positions.size());
  for (std::size_t i = 0; i < group.size(); ++i)
    group[i] = ids.emplace(key_of(i), static_cast<std::uint32_t>(ids.size())).first->second;
  return group;
}

// Area-weighted vertex normals of the deformed faces, summed over each smooth-surface vertex of the rest pose.
void recompute_normals(TriangleMesh& mesh, const TriangleMesh& rest) {
  const std::vector<std::uint32_t> group = smooth_groups(rest);
  std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    sum[group[a]] += n, sum[group[b]] += n, sum[group[c]] += n;
  }
  for (std::size_t i = 0; i < sum.size(); ++i) {
    float length = glm::length(sum[group[i]]);
    if (length > 0.0f) mesh.normals[i] = sum[group[i]] / length;
  }
}

}  // namespace

TriangleMesh deformed_mesh(const TriangleMesh& mesh, const Deformation& d, double seconds) {
  if (d.type == DeformationType::None || mesh.positions.empty()) return mesh;
  float y_min = 1e30f, y_max = -1e30f;
  for (const glm::vec3& p : mesh.positions) y_min = std::min(y_min, p.y), y_max = std::max(y_max, p.y);
  float height = std::max(y_max - y_min, 1e-6f);
  double phase = kTwoPi * (seconds + d.start_s) / std::max(1e-3f, d.period_s);
  TriangleMesh out = mesh;
  for (glm::vec3& p : out.positions) {
    float h = (p.y - y_min) / height;  // 0 at the base, 1 at the top
    switch (d.type) {
      case DeformationType::Bend:  // sways about the base, displacement growing with height squared
        p.x += d.amplitude * static_cast<float>(std::sin(phase)) * h * h;
        break;
      case DeformationType::Wave:  // a travelling ripple up the object
        p.x += d.amplitude * h * static_cast<float>(std::sin(phase - kTwoPi * h));
        break;
      case DeformationType::Melt: {  // sinks and spreads at the base, then recovers (periodic)
        float melt = d.amplitude * static_cast<float>(0.5 - 0.5 * std::cos(phase));
        float spread = 1.0f + melt * (1.0f - h) * (1.0f - h);
        p = glm::vec3(p.x * spread, y_min + (p.y - y_min) * (1.0f - melt * h), p.z * spread);
        break;
      }
      case DeformationType::None:
        break;
    }
  }
  recompute_normals(out, mesh);  // texture coordinates stay those of the rest pose
  return out;
}

Scene scene_at_time(const Scene& scene, double seconds) {
  Scene frozen = scene;
  for (SceneObject& object : frozen.objects) {
    if (object.material && object.material->field.heterogeneous() && !object.material->field.has_bounds) {
      // The field stays where the undeformed object is (voxel-paths places it there too).
      MediumField& field = object.material->field;
      field.bounds_lower = glm::vec3(std::numeric_limits<float>::max()), field.bounds_upper = -field.bounds_lower;
      for (const glm::vec3& p : transformed(object.mesh, object.world_from_object).positions)
        field.bounds_lower = glm::min(field.bounds_lower, p), field.bounds_upper = glm::max(field.bounds_upper, p);
      field.has_bounds = object.blob_resolution == 0;
    }
    if (object.blob_resolution > 0) {
      object.mesh = geometry::extract_blob_isosurface(geometry::blob_grid(object.blob_resolution),
                                                      static_cast<float>(seconds));
      object.blob_resolution = 0;
    }
    object.mesh = deformed_mesh(object.mesh, object.deformation, seconds);
    object.deformation.type = DeformationType::None;
  }
  return frozen;
}

}  // namespace lucent
