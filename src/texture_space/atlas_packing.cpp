// atlas_packing.cpp: see atlas_packing.h.
#include "texture_space/atlas_packing.h"

#include <algorithm>
#include <cmath>

namespace lucent::texture_space {
namespace {

// Skyline (bottom-left) packing at one scale; false when the boxes do not fit. The skyline is the upper outline
// of what is placed, as segments left to right; each box goes where its top ends lowest (then leftmost), resting on
// the highest segment under it. Boxes come in the caller's order (tallest first packs best).
bool pack_at(const std::vector<glm::dvec2>& extents, int size, int gap, double scale, std::vector<PackedBox>& out) {
  struct Segment {
    double x, y, width;
  };
  std::vector<Segment> skyline = {{0.0, 0.0, static_cast<double>(size)}};
  out.resize(extents.size());
  const double half_gap = 0.5 * gap;
  for (std::size_t i = 0; i < extents.size(); ++i) {
    const double w = std::ceil(extents[i].x * scale) + gap, h = std::ceil(extents[i].y * scale) + gap;
    double best_top = 1e300, best_x = 0.0, best_y = 0.0;
    std::size_t best = skyline.size();
    for (std::size_t s = 0; s < skyline.size(); ++s) {
      const double x = skyline[s].x;
      if (x + w > size) break;
      // The box spans segments s.. until their widths cover w; it rests on the highest of them.
      double y = 0.0, covered = 0.0;
      for (std::size_t t = s; t < skyline.size() && covered < w; ++t) y = std::max(y, skyline[t].y), covered += skyline[t].width;
      if (y + h > size) continue;
      if (y + h < best_top) best_top = y + h, best_x = x, best_y = y, best = s;
    }
    if (best == skyline.size()) return false;
    out[i].origin = {best_x + half_gap, best_y + half_gap};
    // The skyline left of the box, the box's top, the skyline right of it.
    std::vector<Segment> next;
    for (const Segment& g : skyline)
      if (g.x < best_x) next.push_back({g.x, g.y, std::min(g.x + g.width, best_x) - g.x});
    next.push_back({best_x, best_y + h, w});
    for (const Segment& g : skyline)
      if (g.x + g.width > best_x + w) {
        const double start = std::max(g.x, best_x + w);
        next.push_back({start, g.y, g.x + g.width - start});
      }
    // Merge neighbours of equal height.
    skyline.clear();
    for (const Segment& g : next) {
      if (!skyline.empty() && skyline.back().y == g.y && skyline.back().x + skyline.back().width == g.x)
        skyline.back().width += g.width;
      else
        skyline.push_back(g);
    }
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
