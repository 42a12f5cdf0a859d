// atlas.h: texture atlases for texture-space subsurface scattering (CPU only, no GL).
//
// Source: Lensch et al. 2002, "Interactive Rendering of Translucent Objects", Section 5.1: the mesh is split into
// charts by normal deviation, each chart is projected orthographically onto a plane facing its normals and packed
// into a square texture with a global scale and at least 3 texels between charts (support of a 7x7 filter). Chang
// et al. 2008 (Eqs. 6-7) then integrate over the atlas with the per-triangle area ratio A_S / A_T, which
// texture_gbuffer.h stores per texel.
//
// Charts (grow_charts): from a seed triangle, edge-adjacent triangles are added (least deviation from the chart's axis
// when they were reached first) while the smallest cone enclosing the chart's normals (its axis turned toward each new
// normal) keeps a half-angle of at most `cone_deg` (triangles of zero area join freely) and the chart stays a
// topological disk (a triangle joins along one edge with its third vertex new to the chart, or along two edges). A
// chart is then checked: every triangle within `cone_deg` of the cone's axis and no two triangles overlapping once
// projected along the axis; a chart that fails is regrown with half the cone (a single triangle always passes). Each
// chart is projected onto the plane of its cone axis and turned to its minimal-area bounding box; the packer
// (atlas_packing.h) places the charts' own texel masks, not their boxes.
//
// Known limits: orthographic projection stretches a triangle tilted by theta against the chart plane by
// 1 / cos(theta) in one direction (at most 2 for a 60 degree cone); texel density is uniform in world space, so
// a small object in a scene with a large one gets few texels.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/mesh.h"

namespace lucent::texture_space {

// Bumped whenever the builder's output changes for the same input (part of the precompute-cache key); 2: charts
// packed by their shapes instead of their bounding boxes.
inline constexpr std::uint32_t kAtlasBuilderVersion = 2;

struct AtlasOptions {
  int size = 1024;              // atlas width = height [texels]
  float cone_deg = 30.0f;       // half-angle of the cone holding a chart's normals: at most 2 cone_deg between two
                                // normals of a chart, 1 / cos(cone_deg) stretch
  int border_texels = 3;        // empty texels at least between the texels any two charts touch
  bool use_own_uvs = true;      // build_scene_atlas: keep a single object's own usable texture coordinates
};

// Distortion of the map from the atlas to the surface, per triangle from the Jacobian J of texture -> surface
// (2x2 in an isometric frame of the triangle) with singular values Gamma >= gamma (Sander et al. 2001):
//   L2 stretch of a triangle  sqrt((Gamma^2 + gamma^2) / 2)
//   stretch_l2   = sqrt(sum_T A_T L2(T)^2 / sum_T A_T) * sqrt(sum_T A'_T / sum_T A_T)
//                  (A_T surface area, A'_T texture area; the second factor removes the global scale, so 1 is an
//                  isometry up to scale, the minimum; stretch_max is the largest Gamma with the same normalisation)
//   angle distortion of a triangle  Gamma / gamma (1: conformal); angle_mean is its surface-area-weighted mean
struct AtlasMetrics {
  int chart_count = 0;
  double utilization = 0.0;   // fraction of the size^2 texels whose centre lies inside a triangle
  double stretch_l2 = 1.0;    // >= 1
  double stretch_max = 1.0;   // >= 1
  double angle_mean = 1.0;    // >= 1
  double angle_max = 1.0;     // >= 1
  double build_ms = 0.0;      // wall clock of build_atlas [ms]
  double texel_size = 0.0;    // edge of one texel on the surface where stretch is 1 [scene units]
};

// One object's share of the atlas.
struct AtlasObject {
  TriangleMesh mesh;                        // the input's positions and normals per corner (not recomputed),
                                            // vertices split at chart seams; uvs in [0, 1]^2, v up (texel row
                                            // y = v * size)
  std::vector<std::uint32_t> source_vertex;  // input vertex of each vertex of `mesh`
  std::vector<std::uint32_t> chart;          // chart of each triangle, numbered over the whole atlas
};

struct Atlas {
  int size = 0;                      // [texels]
  std::vector<AtlasObject> objects;  // in the order given; charts of all objects packed together
  AtlasMetrics metrics;
};

// One object to lay out: its mesh in object space and the transform that places it, so that charts are cut,
// projected and scaled in world space (uniform texel size over all objects; a deforming object uses its rest pose).
struct AtlasInput {
  const TriangleMesh* mesh = nullptr;
  glm::mat4 world_from_object{1.0f};
};

// Builds one atlas holding every input's charts. Throws lucent::Error when the charts do not fit at `size` with
// their borders (more charts than the texture has room for at one texel each).
Atlas build_atlas(std::span<const AtlasInput> inputs, const AtlasOptions& options);
Atlas build_atlas(const TriangleMesh& mesh, const AtlasOptions& options);

// Why the mesh's own texture coordinates cannot serve as an atlas of `size` texels, or nothing when they can:
// missing, outside [0, 1]^2, a triangle of zero texture area, or two triangles overlapping (tested at the centres
// of a 2 size x 2 size grid, edges excluded). Two charts closer than a texel are not detected.
std::optional<std::string> uv_problem(const TriangleMesh& mesh, int size);

// The metrics of texture coordinates already present (chart_count and build_ms are left 0).
AtlasMetrics uv_metrics(const TriangleMesh& mesh, int size);

}  // namespace lucent::texture_space
