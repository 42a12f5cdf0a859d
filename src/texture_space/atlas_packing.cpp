// atlas_packing.cpp: see atlas_packing.h.
#include "texture_space/atlas_packing.h"

#include <algorithm>
#include <cmath>

namespace lucent::texture_space {
namespace {

// Shelf packing at one scale; false when the boxes do not fit.
bool pack_at(const std::vector<glm::dvec2>& extents, int size, int gap, double scale, std::vector<PackedBox>& out) {
  out.resize(extents.size());
  double x = 0.0, y = 0.0, shelf = 0.0;
  const double half_gap = 0.5 * gap;
  for (std::size_t i = 0; i < extents.size(); ++i) {
    double w = std::ceil(extents[i].x * scale) + gap, h = std::ceil(extents[i].y * scale) + gap;
    if (x + w > size) x = 0.0, y += shelf, shelf = 0.0;
    if (x + w > size || y + h > size) return false;
    out[i].origin = {x + half_gap, y + half_gap};
    x += w, shelf = std::max(shelf, h);
  }
  return true;
}

}  // namespace

double pack_boxes(const std::vector<glm::dvec2>& extents, int size, int gap, std::vector<PackedBox>& out) {
  double area = 0.0;
  for (glm::dvec2 e : extents) area += e.x * e.y;
  // The boxes' own area bounds the scale from above; the smallest scale leaves each box (1 + gap) texels wide.
  double lo = 1e-9 / std::max(1e-30, std::sqrt(area)), hi = size / std::max(1e-30, std::sqrt(area));
  for (glm::dvec2 e : extents) hi = std::min(hi, (size - gap) / std::max(1e-30, std::max(e.x, e.y)));
  if (!pack_at(extents, size, gap, lo, out)) return 0.0;
  if (pack_at(extents, size, gap, hi, out)) return hi;
  for (int i = 0; i < 48; ++i) {
    double mid = 0.5 * (lo + hi);
    (pack_at(extents, size, gap, mid, out) ? lo : hi) = mid;
  }
  pack_at(extents, size, gap, lo, out);
  return lo;
}

}  // namespace lucent::texture_space
