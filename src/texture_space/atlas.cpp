// atlas.cpp: see atlas.h. Charts (charts.cpp) turned to their minimal-area boxes, packing by their shapes
// (atlas_packing.cpp), texture coordinates with vertices split at seams, and the metrics.
#include "texture_space/atlas.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <fmt/format.h>

#include "lucent/error.h"
#include "texture_space/atlas_packing.h"
#include "texture_space/charts.h"
#include "texture_space/uv_raster.h"

namespace lucent::texture_space {
namespace {

// A chart's corners projected and rotated to its minimal-area bounding box, lower corner at the origin.
struct PlacedChart {
  std::uint32_t object = 0;
  Chart chart;
  std::vector<glm::dvec2> corners;  // three per chart triangle [scene units]
  double area = 0.0;                // of its triangles [scene units^2]
};

std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> points) {
  std::sort(points.begin(), points.end(), [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (points.size() < 3) return points;
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower hull
    while (k >= 2 && signed_area2(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && signed_area2(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// Rotates the corners so that their bounding box has minimal area (one box side lies on a hull edge), wider than tall.
void fit_minimal_box(PlacedChart& placed) {
  std::vector<glm::dvec2> hull = convex_hull(placed.corners);
  double best_area = 1e300, best_angle = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    glm::dvec2 edge = hull[(i + 1) % hull.size()] - hull[i];
    if (glm::length(edge) <= 0.0) continue;
    glm::dvec2 u = glm::normalize(edge), v(-u.y, u.x);
    glm::dvec2 lo(1e300), hi(-1e300);
    for (glm::dvec2 p : hull) lo = glm::min(lo, glm::dvec2(glm::dot(p, u), glm::dot(p, v))), hi = glm::max(hi, glm::dvec2(glm::dot(p, u), glm::dot(p, v)));
    double area = (hi.x - lo.x) * (hi.y - lo.y);
    if (area < best_area) best_area = area, best_angle = std::atan2(u.y, u.x);
  }
  glm::dvec2 u(std::cos(best_angle), std::sin(best_angle)), v(-u.y, u.x);
  glm::dvec2 lo(1e300), hi(-1e300);
  for (glm::dvec2& p : placed.corners) {
    p = {glm::dot(p, u), glm::dot(p, v)};
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  bool turn = hi.y - lo.y > hi.x - lo.x;  // a quarter turn (counter-clockwise, orientation kept) makes it wide
  for (glm::dvec2& p : placed.corners) {
    p -= lo;
    if (turn) p = {hi.y - lo.y - p.y, p.x};
  }
}

std::vector<PlacedChart> chart_object(const TriangleMesh& world, std::uint32_t object, float cone_deg) {
  std::vector<PlacedChart> out;
  for (Chart& chart : grow_charts(world.positions, world.indices, cone_deg)) {
    PlacedChart placed;
    placed.object = object;
    for (std::uint32_t f : chart.triangles)
      for (int c = 0; c < 3; ++c) placed.corners.push_back(project(world.positions[world.indices[3 * f + c]], chart.normal));
    placed.chart = std::move(chart);
    fit_minimal_box(placed);
    for (std::size_t t = 0; t < placed.corners.size(); t += 3)
      placed.area += 0.5 * std::abs(signed_area2(placed.corners[t], placed.corners[t + 1], placed.corners[t + 2]));
    out.push_back(std::move(placed));
  }
  return out;
}

// The object's mesh with one vertex per (input vertex, chart) and texture coordinates from the packed charts.
void emit_object(const TriangleMesh& input, const std::vector<const PlacedChart*>& charts,
                 const std::vector<std::uint32_t>& chart_ids, const std::vector<std::vector<glm::dvec2>>& texels,
                 int size, AtlasObject& out) {
  const std::size_t triangles = input.indices.size() / 3;
  out.mesh.indices.resize(input.indices.size());
  out.chart.resize(triangles);
  std::unordered_map<std::uint64_t, std::uint32_t> vertex_of;
  for (std::size_t k = 0; k < charts.size(); ++k) {
    const PlacedChart& placed = *charts[k];
    const std::uint32_t id = chart_ids[k];
    for (std::size_t t = 0; t < placed.chart.triangles.size(); ++t) {
      std::uint32_t f = placed.chart.triangles[t];
      out.chart[f] = id;
      for (int c = 0; c < 3; ++c) {
        std::uint32_t source = input.indices[3 * f + c];
        auto [it, inserted] = vertex_of.try_emplace(std::uint64_t{id} << 32 | source, static_cast<std::uint32_t>(out.mesh.positions.size()));
        if (inserted) {
          glm::dvec2 texel = texels[id][3 * t + c];
          out.mesh.positions.push_back(input.positions[source]);
          out.mesh.normals.push_back(input.normals[source]);
          out.mesh.uvs.emplace_back(texel / static_cast<double>(size));
          out.source_vertex.push_back(source);
        }
        out.mesh.indices[3 * f + c] = it->second;
      }
    }
  }
}

struct TriangleDistortion {
  double area = 0.0, texture_area = 0.0;  // [scene units^2], [uv units^2]
  double sigma_max = 0.0, sigma_min = 0.0; // singular values of texture -> surface [scene units / uv unit]
};

TriangleDistortion distortion(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec2 ta, glm::dvec2 tb, glm::dvec2 tc) {
  TriangleDistortion d;
  glm::dvec3 e1 = b - a, e2 = c - a;
  double cross = glm::length(glm::cross(e1, e2)), length1 = glm::length(e1);
  d.area = 0.5 * cross;
  d.texture_area = 0.5 * std::abs(signed_area2(ta, tb, tc));
  if (d.area <= 0.0 || d.texture_area <= 0.0) return d;
  // Surface edges in an isometric frame of the triangle; J = Q T^-1 maps texture offsets to surface offsets.
  glm::dmat2 q(glm::dvec2(length1, 0.0), glm::dvec2(glm::dot(e1, e2) / length1, cross / length1));
  glm::dmat2 t(tb - ta, tc - ta);
  glm::dmat2 j = q * glm::inverse(t);
  // Singular values of a 2x2 matrix from its Frobenius norm and determinant.
  double f = j[0][0] * j[0][0] + j[0][1] * j[0][1] + j[1][0] * j[1][0] + j[1][1] * j[1][1];
  double det = std::abs(glm::determinant(j));
  double root = std::sqrt(std::max(0.0, f * f - 4.0 * det * det));
  d.sigma_max = std::sqrt(0.5 * (f + root));
  d.sigma_min = std::sqrt(std::max(0.0, 0.5 * (f - root)));
  return d;
}

struct MetricInput {
  const TriangleMesh* mesh;
  glm::mat4 world_from_object;
};

AtlasMetrics compute_metrics(const std::vector<MetricInput>& inputs, int size) {
  AtlasMetrics m;
  std::vector<TriangleDistortion> all;
  std::vector<unsigned char> covered(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0);
  for (const MetricInput& input : inputs) {
    TriangleMesh world = transformed(*input.mesh, input.world_from_object);  // positions only
    const std::vector<glm::vec2>& uvs = input.mesh->uvs;
    for (std::size_t f = 0; f + 2 < world.indices.size(); f += 3) {
      std::uint32_t i = world.indices[f], j = world.indices[f + 1], k = world.indices[f + 2];
      glm::dvec2 ta = uvs[i], tb = uvs[j], tc = uvs[k];
      all.push_back(distortion(world.positions[i], world.positions[j], world.positions[k], ta, tb, tc));
      for_each_cell_inside(ta, tb, tc, size, 0.0, [&](int x, int y) { covered[static_cast<std::size_t>(y * size + x)] = 1; });
    }
  }
  double area = 0.0, texture_area = 0.0, l2 = 0.0, angle = 0.0, max_sigma = 0.0;
  for (const TriangleDistortion& d : all) {
    if (d.area <= 0.0 || d.texture_area <= 0.0 || d.sigma_min <= 0.0) continue;
    area += d.area, texture_area += d.texture_area;
    l2 += d.area * 0.5 * (d.sigma_max * d.sigma_max + d.sigma_min * d.sigma_min);
    angle += d.area * d.sigma_max / d.sigma_min;
    max_sigma = std::max(max_sigma, d.sigma_max);
    m.angle_max = std::max(m.angle_max, d.sigma_max / d.sigma_min);
  }
  if (area > 0.0) {
    double normalisation = std::sqrt(texture_area / area);
    m.stretch_l2 = std::sqrt(l2 / area) * normalisation;
    m.stretch_max = max_sigma * normalisation;
    m.angle_mean = angle / area;
    m.texel_size = std::sqrt(area / texture_area) / size;
  }
  m.utilization = static_cast<double>(std::count(covered.begin(), covered.end(), 1)) / static_cast<double>(covered.size());
  return m;
}

}  // namespace

Atlas build_atlas(std::span<const AtlasInput> inputs, const AtlasOptions& options) {
  auto start = std::chrono::steady_clock::now();
  // Charts of every object in world space, numbered object by object; packed in order of decreasing area (large
  // charts first pack best).
  std::vector<PlacedChart> charts;
  for (std::size_t o = 0; o < inputs.size(); ++o)
    for (PlacedChart& c : chart_object(transformed(*inputs[o].mesh, inputs[o].world_from_object),
                                       static_cast<std::uint32_t>(o), options.cone_deg))
      charts.push_back(std::move(c));
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return charts[a].area > charts[b].area; });
  std::vector<std::vector<glm::dvec2>> shapes, packed, texels(charts.size());
  for (std::size_t i : order) shapes.push_back(charts[i].corners);
  const double scale = pack_charts(shapes, options.size, options.border_texels, packed);
  if (scale <= 0.0)
    throw Error(fmt::format("{} charts do not fit into a {} x {} atlas with {}-texel borders; use a larger size",
                            charts.size(), options.size, options.size, options.border_texels));
  for (std::size_t i = 0; i < order.size(); ++i) texels[order[i]] = std::move(packed[i]);
  Atlas atlas;
  atlas.size = options.size;
  for (std::size_t o = 0; o < inputs.size(); ++o) {
    std::vector<const PlacedChart*> mine;
    std::vector<std::uint32_t> ids;
    for (std::size_t c = 0; c < charts.size(); ++c)
      if (charts[c].object == o) mine.push_back(&charts[c]), ids.push_back(static_cast<std::uint32_t>(c));
    AtlasObject object;
    emit_object(*inputs[o].mesh, mine, ids, texels, options.size, object);
    atlas.objects.push_back(std::move(object));
  }
  std::vector<MetricInput> metric_inputs;
  for (std::size_t o = 0; o < inputs.size(); ++o) metric_inputs.push_back({&atlas.objects[o].mesh, inputs[o].world_from_object});
  atlas.metrics = compute_metrics(metric_inputs, options.size);
  atlas.metrics.chart_count = static_cast<int>(charts.size());
  atlas.metrics.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return atlas;
}

Atlas build_atlas(const TriangleMesh& mesh, const AtlasOptions& options) {
  AtlasInput input{&mesh, glm::mat4(1.0f)};
  return build_atlas(std::span<const AtlasInput>(&input, 1), options);
}

AtlasMetrics uv_metrics(const TriangleMesh& mesh, int size) {
  return compute_metrics({{&mesh, glm::mat4(1.0f)}}, size);
}

std::optional<std::string> uv_problem(const TriangleMesh& mesh, int size) {
  if (mesh.uvs.empty()) return "the mesh has no texture coordinates";
  if (mesh.uvs.size() != mesh.positions.size())
    return fmt::format("{} texture coordinates for {} vertices", mesh.uvs.size(), mesh.positions.size());
  for (std::size_t v = 0; v < mesh.uvs.size(); ++v) {
    glm::vec2 t = mesh.uvs[v];
    if (!(t.x >= 0.0f && t.x <= 1.0f && t.y >= 0.0f && t.y <= 1.0f))
      return fmt::format("texture coordinate {} = ({}, {}) lies outside [0, 1]^2", v, t.x, t.y);
  }
  const std::size_t triangles = mesh.indices.size() / 3;
  for (std::size_t f = 0; f < triangles; ++f) {
    glm::dvec2 a = mesh.uvs[mesh.indices[3 * f]], b = mesh.uvs[mesh.indices[3 * f + 1]], c = mesh.uvs[mesh.indices[3 * f + 2]];
    if (signed_area2(a, b, c) == 0.0) return fmt::format("triangle {} has zero area in texture space", f);
  }
  // Overlaps: every centre of a 2 size x 2 size grid strictly inside at most one triangle.
  const int grid = 2 * size;
  std::vector<std::uint32_t> owner(static_cast<std::size_t>(grid) * static_cast<std::size_t>(grid), 0);  // triangle + 1
  for (std::size_t f = 0; f < triangles; ++f) {
    glm::dvec2 a = mesh.uvs[mesh.indices[3 * f]], b = mesh.uvs[mesh.indices[3 * f + 1]], c = mesh.uvs[mesh.indices[3 * f + 2]];
    std::optional<std::string> problem;
    for_each_cell_inside(a, b, c, grid, 1e-6, [&](int x, int y) {
      std::uint32_t& cell = owner[static_cast<std::size_t>(y * grid + x)];
      if (cell != 0 && !problem)
        problem = fmt::format("triangles {} and {} overlap in texture space (at u = {:.4f}, v = {:.4f})", cell - 1, f,
                              (x + 0.5) / grid, (y + 0.5) / grid);
      cell = static_cast<std::uint32_t>(f + 1);
    });
    if (problem) return problem;
  }
  return std::nullopt;
}

}  // namespace lucent::texture_space
