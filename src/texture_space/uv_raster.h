// uv_raster.h: the texture-space triangle rasterizer of the CPU side (atlas checks, utilization, tests): visits the
// cells of an n x n grid over [0, 1]^2 whose centre lies strictly inside a triangle given in texture coordinates.
#pragma once
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace lucent::texture_space {

// Twice the signed area of (a, b, c): positive when counter-clockwise.
inline double signed_area2(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Calls visit(x, y) for each cell (x, y) of the n x n grid whose centre ((x + 0.5) / n, (y + 0.5) / n) lies inside
// the triangle by more than `margin` (in units of the triangle's own barycentric coordinates, so shared edges and
// vertices are excluded for margin > 0). Either orientation; degenerate triangles visit nothing.
template <typename Visit>
void for_each_cell_inside(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, int n, double margin, Visit&& visit) {
  const double area2 = signed_area2(a, b, c);
  if (std::abs(area2) <= 1e-300) return;
  const double scale = static_cast<double>(n);
  glm::dvec2 lo = glm::min(a, glm::min(b, c)) * scale, hi = glm::max(a, glm::max(b, c)) * scale;
  int x0 = std::max(0, static_cast<int>(std::floor(lo.x - 0.5))), x1 = std::min(n - 1, static_cast<int>(std::ceil(hi.x - 0.5)));
  int y0 = std::max(0, static_cast<int>(std::floor(lo.y - 0.5))), y1 = std::min(n - 1, static_cast<int>(std::ceil(hi.y - 0.5)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      glm::dvec2 p((x + 0.5) / scale, (y + 0.5) / scale);
      double l0 = signed_area2(b, c, p) / area2, l1 = signed_area2(c, a, p) / area2, l2 = 1.0 - l0 - l1;
      if (l0 > margin && l1 > margin && l2 > margin) visit(x, y);
    }
}

}  // namespace lucent::texture_space
