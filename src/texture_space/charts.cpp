// charts.cpp: see charts.h.
#include "texture_space/charts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <queue>
#include <unordered_map>

#include "texture_space/uv_raster.h"

namespace lucent::texture_space {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// The mesh as charting sees it: welded vertices, triangle normals and areas, edge neighbours.
struct Topology {
  std::vector<std::uint32_t> corners;                  // welded vertex per triangle corner
  std::vector<glm::dvec3> normal;                      // unit, per triangle (0 when degenerate)
  std::vector<double> area;                            // per triangle [scene units^2]
  std::vector<std::array<std::uint32_t, 3>> neighbour; // across edge (c, c + 1), or kNone
  std::vector<glm::dvec3> position;                    // per welded vertex
};

std::vector<std::uint32_t> weld(const std::vector<glm::vec3>& positions, std::vector<glm::dvec3>& welded) {
  struct Key {
    std::uint32_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const { return (k.x * 73856093u) ^ (k.y * 19349663u) ^ (k.z * 83492791u); }
  };
  std::unordered_map<Key, std::uint32_t, Hash> ids;
  std::vector<std::uint32_t> out(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    glm::vec3 p = positions[v] + glm::vec3(0.0f);  // -0 == +0
    Key key{};
    std::memcpy(&key.x, &p.x, 4), std::memcpy(&key.y, &p.y, 4), std::memcpy(&key.z, &p.z, 4);
    auto [it, inserted] = ids.try_emplace(key, static_cast<std::uint32_t>(welded.size()));
    if (inserted) welded.emplace_back(p);
    out[v] = it->second;
  }
  return out;
}

Topology build_topology(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  Topology t;
  std::vector<std::uint32_t> id = weld(positions, t.position);
  const std::size_t triangles = indices.size() / 3;
  t.corners.resize(indices.size());
  for (std::size_t c = 0; c < indices.size(); ++c) t.corners[c] = id[indices[c]];
  t.normal.resize(triangles), t.area.resize(triangles);
  for (std::size_t f = 0; f < triangles; ++f) {
    glm::dvec3 a = t.position[t.corners[3 * f]], b = t.position[t.corners[3 * f + 1]], c = t.position[t.corners[3 * f + 2]];
    glm::dvec3 n = glm::cross(b - a, c - a);
    double length = glm::length(n);
    t.area[f] = 0.5 * length;
    t.normal[f] = length > 0.0 ? n / length : glm::dvec3(0.0);
  }
  // Edges sorted by their two welded vertices: runs of exactly two triangles are manifold neighbours.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges(indices.size());
  for (std::size_t c = 0; c < indices.size(); ++c) {
    std::uint64_t u = t.corners[c], v = t.corners[c - c % 3 + (c + 1) % 3];
    edges[c] = {std::min(u, v) << 32 | std::max(u, v), static_cast<std::uint32_t>(c)};
  }
  std::sort(edges.begin(), edges.end());
  t.neighbour.assign(triangles, {kNone, kNone, kNone});
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 2) {
      std::uint32_t c0 = edges[i].second, c1 = edges[i + 1].second;
      t.neighbour[c0 / 3][c0 % 3] = c1 / 3;
      t.neighbour[c1 / 3][c1 % 3] = c0 / 3;
    }
    i = j;
  }
  return t;
}

// A cone of directions: every normal added so far is within half_angle of axis.
struct NormalCone {
  glm::dvec3 axis;
  double half_angle;  // [radians]
  // The smallest cone holding this one and n: the axis turns toward n by half the excess angle.
  NormalCone enclosing(glm::dvec3 n) const {
    double theta = std::acos(std::clamp(glm::dot(axis, n), -1.0, 1.0));
    if (theta <= half_angle) return *this;
    if (theta >= 3.14159) return {axis, 3.14159};
    double turn = 0.5 * (theta - half_angle);
    glm::dvec3 side = glm::normalize(n - axis * glm::dot(axis, n));
    return {glm::normalize(axis * std::cos(turn) + side * std::sin(turn)), 0.5 * (theta + half_angle)};
  }
};

// Grows one chart from `seed` over triangles with owner[f] == free_mark, marking them with chart_mark.
class ChartGrower {
 public:
  explicit ChartGrower(const Topology& topology) : t_(topology), vertex_use_(topology.position.size(), 0) {}

  // Grows the chart and returns its triangles; `axis` receives the axis of the cone enclosing their normals.
  std::vector<std::uint32_t> grow(std::uint32_t seed, std::vector<std::uint32_t>& owner, std::uint32_t free_mark,
                                  std::uint32_t chart_mark, double cone_rad, glm::dvec3& axis) {
    std::vector<std::uint32_t> members;
    NormalCone cone{t_.normal[seed], 0.0};
    using Candidate = std::pair<double, std::uint32_t>;  // (deviation from the axis, triangle), smallest first
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue;
    auto add = [&](std::uint32_t f) {
      owner[f] = chart_mark;
      members.push_back(f);
      for (int c = 0; c < 3; ++c) ++vertex_use_[t_.corners[3 * f + c]];
      for (std::uint32_t g : t_.neighbour[f])
        if (g != kNone && owner[g] == free_mark) queue.push({1.0 - glm::dot(t_.normal[g], cone.axis), g});
    };
    add(seed);
    while (!queue.empty()) {
      std::uint32_t f = queue.top().second;
      queue.pop();
      if (owner[f] != free_mark || !keeps_disk(f, owner, chart_mark)) continue;
      if (t_.area[f] <= 0.0) {
        add(f);
        continue;
      }
      NormalCone grown = cone.enclosing(t_.normal[f]);
      if (grown.half_angle <= cone_rad) cone = grown, add(f);
    }
    for (std::uint32_t f : members)
      for (int c = 0; c < 3; ++c) vertex_use_[t_.corners[3 * f + c]] = 0;
    axis = cone.axis;
    return members;
  }

 private:
  // A disk stays a disk when the triangle joins along two edges, or along one edge with its third vertex new.
  bool keeps_disk(std::uint32_t f, const std::vector<std::uint32_t>& owner, std::uint32_t chart_mark) const {
    int shared = 0, joined_edge = -1;
    for (int e = 0; e < 3; ++e)
      if (t_.neighbour[f][e] != kNone && owner[t_.neighbour[f][e]] == chart_mark) ++shared, joined_edge = e;
    if (shared == 2) return true;
    if (shared != 1) return false;
    std::uint32_t opposite = t_.corners[3 * f + (joined_edge + 2) % 3];
    return vertex_use_[opposite] == 0;
  }

  const Topology& t_;
  std::vector<int> vertex_use_;  // chart triangles using each welded vertex (zeroed after each chart)
};

// Every triangle within the cone around the chart's axis, and free of overlaps once projected along it.
bool chart_is_valid(const Topology& t, const Chart& chart, double cos_cone) {
  std::vector<glm::dvec2> corners;
  corners.reserve(3 * chart.triangles.size());
  for (std::uint32_t f : chart.triangles) {
    if (t.area[f] > 0.0 && glm::dot(t.normal[f], chart.normal) < cos_cone - 1e-6) return false;
    for (int c = 0; c < 3; ++c) corners.push_back(project(t.position[t.corners[3 * f + c]], chart.normal));
  }
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (glm::dvec2 p : corners) lo = glm::min(lo, p), hi = glm::max(hi, p);
  double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  return !projected_triangles_overlap(corners, 1e-7 * extent);
}


// Charts over the triangles marked free_mark; invalid charts are regrown with half the cone.
void grow_into(const Topology& t, ChartGrower& grower, const std::vector<std::uint32_t>& triangles,
               std::vector<std::uint32_t>& owner, std::uint32_t free_mark, double cone_rad, std::vector<Chart>& out) {
  const double cos_cone = std::cos(cone_rad);
  for (std::uint32_t seed : triangles) {
    if (owner[seed] != free_mark) continue;
    auto chart_mark = static_cast<std::uint32_t>(out.size());
    Chart chart;
    chart.triangles = grower.grow(seed, owner, free_mark, chart_mark, cone_rad, chart.normal);
    if (!(glm::length(chart.normal) > 0.5)) chart.normal = {0.0, 0.0, 1.0};  // a degenerate seed
    if (chart.triangles.size() == 1 || chart_is_valid(t, chart, cos_cone)) {
      out.push_back(std::move(chart));
      continue;
    }
    // Regrow this chart's triangles with a narrower cone; they are marked free with a mark no chart uses.
    const std::uint32_t retry_mark = kNone - 1 - static_cast<std::uint32_t>(out.size());
    for (std::uint32_t f : chart.triangles) owner[f] = retry_mark;
    grow_into(t, grower, chart.triangles, owner, retry_mark, 0.5 * cone_rad, out);
  }
}

double axis_gap(const glm::dvec2* a, const glm::dvec2* b, glm::dvec2 axis) {
  double a_lo = 1e300, a_hi = -1e300, b_lo = 1e300, b_hi = -1e300;
  for (int i = 0; i < 3; ++i) {
    double pa = glm::dot(a[i], axis), pb = glm::dot(b[i], axis);
    a_lo = std::min(a_lo, pa), a_hi = std::max(a_hi, pa), b_lo = std::min(b_lo, pb), b_hi = std::max(b_hi, pb);
  }
  return std::max(b_lo - a_hi, a_lo - b_hi);
}

// Separating axis test over the six edge normals (enough for two convex polygons in 2D).
bool triangles_overlap(const glm::dvec2* a, const glm::dvec2* b, double tolerance) {
  for (const glm::dvec2* tri : {a, b})
    for (int e = 0; e < 3; ++e) {
      glm::dvec2 edge = tri[(e + 1) % 3] - tri[e];
      double length = glm::length(edge);
      if (length <= 0.0) continue;
      if (axis_gap(a, b, glm::dvec2(-edge.y, edge.x) / length) >= -tolerance) return false;
    }
  return std::abs(signed_area2(a[0], a[1], a[2])) > 0.0 && std::abs(signed_area2(b[0], b[1], b[2])) > 0.0;
}

}  // namespace

glm::dvec2 project(glm::dvec3 p, glm::dvec3 normal) {
  glm::dvec3 helper = std::abs(normal.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  glm::dvec3 tangent = glm::normalize(glm::cross(helper, normal));
  glm::dvec3 bitangent = glm::cross(normal, tangent);
  return {glm::dot(p, tangent), glm::dot(p, bitangent)};
}

bool projected_triangles_overlap(const std::vector<glm::dvec2>& corners, double tolerance) {
  const std::size_t n = corners.size() / 3;
  if (n < 2) return false;
  // Uniform grid of about one triangle per cell; each pair is tested in every cell both touch.
  glm::dvec2 lo(1e300), hi(-1e300);
  for (glm::dvec2 p : corners) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const int cells = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(n))), 1, 512);
  glm::dvec2 cell_size = glm::max((hi - lo) / static_cast<double>(cells), glm::dvec2(1e-300));
  std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(cells) * static_cast<std::size_t>(cells));
  auto cell_of = [&](double v, double origin, double size) {
    return std::clamp(static_cast<int>((v - origin) / size), 0, cells - 1);
  };
  for (std::size_t f = 0; f < n; ++f) {
    const glm::dvec2* tri = &corners[3 * f];
    glm::dvec2 a = glm::min(tri[0], glm::min(tri[1], tri[2])), b = glm::max(tri[0], glm::max(tri[1], tri[2]));
    for (int y = cell_of(a.y, lo.y, cell_size.y); y <= cell_of(b.y, lo.y, cell_size.y); ++y)
      for (int x = cell_of(a.x, lo.x, cell_size.x); x <= cell_of(b.x, lo.x, cell_size.x); ++x)
        grid[static_cast<std::size_t>(y * cells + x)].push_back(static_cast<std::uint32_t>(f));
  }
  for (const std::vector<std::uint32_t>& cell : grid)
    for (std::size_t i = 0; i < cell.size(); ++i)
      for (std::size_t j = i + 1; j < cell.size(); ++j)
        if (triangles_overlap(&corners[3 * cell[i]], &corners[3 * cell[j]], tolerance)) return true;
  return false;
}

std::vector<Chart> grow_charts(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices,
                               float cone_deg) {
  Topology topology = build_topology(positions, indices);
  ChartGrower grower(topology);
  const std::uint32_t free_mark = kNone;
  std::vector<std::uint32_t> owner(indices.size() / 3, free_mark), order(indices.size() / 3);
  for (std::size_t f = 0; f < order.size(); ++f) order[f] = static_cast<std::uint32_t>(f);
  std::vector<Chart> charts;
  grow_into(topology, grower, order, owner, free_mark, glm::radians(static_cast<double>(cone_deg)), charts);
  return charts;
}

}  // namespace lucent::texture_space
