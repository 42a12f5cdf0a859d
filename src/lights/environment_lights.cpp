// environment_lights.cpp: an environment map turned into M directional lights (Dal Corso et al. 2015, Sec. 4,
// Fig. 15). Every method cuts the sphere into at most M regions; power is luminance x solid angle, i.e.
// luminance x sin(theta) in (u, v).
//   median cut:   P. Debevec, "A Median Cut Algorithm for Light Probe Sampling", SIGGRAPH 2005 poster; regions
//                 are pixel rectangles, the most powerful one is split across its angularly longest side
//                 (u extent scaled by sin(theta) at its middle row) at the pixel boundary closest to half its power.
//   stratified:   M. Pharr, G. Humphreys, Physically Based Rendering, 2nd ed., Sec. 14.6.5 (piecewise-constant
//                 2D distribution); the primary sample square is cut into nv x nu cells (nv = the largest divisor
//                 of M not above sqrt(M)), each cell's preimage being a band of rows and, within each row, a run
//                 of pixels, with fractional pixels at the ends.
//   variance cut: rectangles again, but the costliest one (power-weighted directional variance, the k-means
//                 cost) is split along u or v where its halves cost least; summed-area tables make each candidate
//                 cut O(1). Like Wu's colour quantiser, on the sphere.
//   k-means:      the variance cut's centroids refined by Lloyd iterations (S. Lloyd 1982); regions become the
//                 centroids' Voronoi cells.
// The first two cut equal power and so spend most lights on a bright sun; the last two bound the irradiance error,
// which for any normal is at most the integral of L |w - mean direction| dw over the region (docs/lights/
// environment.md has the measurements). Each region becomes one light from its luminance-weighted mean direction
// carrying the region's RGB integral of L dw, so the total is preserved exactly (up to rounding).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <queue>
#include <vector>

#include <fmt/format.h>

#include "lights/equirect.h"
#include "lucent/environment.h"
#include "lucent/error.h"

namespace lucent {
namespace {

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// The map's pixels as powers: only the luminance weights are stored (8 bytes a pixel, for large maps).
struct PixelPowers {
  explicit PixelPowers(const EnvironmentMap& environment) : map(environment), width(map.width), height(map.height) {
    for (int y = 0; y < height; ++y) solid_angle.push_back(shader::equirect_pixel_solid_angle(y, width, height));
    weight.reserve(map.radiance.size());
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) weight.push_back(luminance(power(x, y)));
  }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
  glm::dvec3 power(int x, int y) const { return glm::dvec3(map.at(x, y)) * solid_angle[static_cast<std::size_t>(y)]; }
  glm::dvec3 direction(int x, int y) const { return glm::dvec3(shader::equirect_pixel_direction(x, y, width, height)); }

  const EnvironmentMap& map;
  int width, height;
  std::vector<double> solid_angle;  // per row [sr]
  std::vector<double> weight;       // luminance of L d_omega: what the regions share equally
};

// Sums of (fractions of) pixels making up one region, and the light standing in for it.
struct RegionSum {
  glm::dvec3 power{0.0};
  glm::dvec3 weighted_direction{0.0};
  double brightest_weight = -1.0;
  glm::dvec3 brightest_direction{0.0, 1.0, 0.0};

  void add(const PixelPowers& pixels, int x, int y, double fraction) {
    const double weight = fraction * pixels.weight[pixels.index(x, y)];
    if (weight <= 0.0) return;
    const glm::dvec3 direction = pixels.direction(x, y);
    power += fraction * pixels.power(x, y);
    weighted_direction += weight * direction;
    if (weight > brightest_weight) {
      brightest_weight = weight;
      brightest_direction = direction;
    }
  }

  // Travels away from the region's mean direction; a region whose mean direction vanishes (the whole sphere of
  // a constant map) shines from its brightest pixel.
  DirectionalLight light() const {
    const double length = glm::length(weighted_direction);
    const double total = luminance(power);
    const glm::dvec3 toward = length > 1.0e-6 * total ? weighted_direction / length : brightest_direction;
    return DirectionalLight{glm::vec3(-toward), glm::vec3(power)};
  }
};

void append_lit(std::vector<DirectionalLight>& lights, const RegionSum& region) {
  if (region.power.r > 0.0 || region.power.g > 0.0 || region.power.b > 0.0) lights.push_back(region.light());
}

// ---- median cut ---------------------------------------------------------------------------------------------

// Summed-area table of the pixel weights: sum over [x0, x1) x [y0, y1) in O(1).
class SummedArea {
 public:
  explicit SummedArea(const PixelPowers& pixels) : stride_(static_cast<std::size_t>(pixels.width) + 1) {
    table_.assign(stride_ * (static_cast<std::size_t>(pixels.height) + 1), 0.0);
    for (int y = 0; y < pixels.height; ++y)
      for (int x = 0; x < pixels.width; ++x)
        table_[at(x + 1, y + 1)] =
            pixels.weight[pixels.index(x, y)] + table_[at(x, y + 1)] + table_[at(x + 1, y)] - table_[at(x, y)];
  }
  double sum(int x0, int x1, int y0, int y1) const {
    return table_[at(x1, y1)] - table_[at(x0, y1)] - table_[at(x1, y0)] + table_[at(x0, y0)];
  }

 private:
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * stride_ + static_cast<std::size_t>(x); }
  std::size_t stride_;
  std::vector<double> table_;
};

struct Rect {
  int x0, x1, y0, y1;  // pixels [x0, x1) x [y0, y1)
  double weight;
};

struct LessPowerful {
  bool operator()(const Rect& a, const Rect& b) const { return a.weight < b.weight; }
};

// Splits r across its angularly longest side (the u extent is scaled by sin(theta) at the middle row) at the
// pixel boundary that leaves the two halves closest to equal weight. False when r is a single pixel.
bool split(const Rect& r, const SummedArea& area, int width, int height, Rect& first, Rect& second) {
  const double sin_theta = std::sin(M_PI * 0.5 * (r.y0 + r.y1) / height);
  const double angular_width = 2.0 * M_PI * (r.x1 - r.x0) / width * sin_theta;
  const double angular_height = M_PI * (r.y1 - r.y0) / height;
  bool along_u = angular_width >= angular_height;
  if (r.x1 - r.x0 == 1) along_u = false;
  if (r.y1 - r.y0 == 1) along_u = true;
  if (r.x1 - r.x0 == 1 && r.y1 - r.y0 == 1) return false;
  const int begin = along_u ? r.x0 : r.y0, end = along_u ? r.x1 : r.y1;
  int best = begin + 1;
  double best_gap = std::numeric_limits<double>::infinity();
  for (int s = begin + 1; s < end; ++s) {
    const double part = along_u ? area.sum(r.x0, s, r.y0, r.y1) : area.sum(r.x0, r.x1, r.y0, s);
    const double gap = std::abs(2.0 * part - r.weight);
    if (gap < best_gap) best_gap = gap, best = s;
  }
  first = r, second = r;
  if (along_u) {
    first.x1 = second.x0 = best;
  } else {
    first.y1 = second.y0 = best;
  }
  first.weight = area.sum(first.x0, first.x1, first.y0, first.y1);
  second.weight = area.sum(second.x0, second.x1, second.y0, second.y1);
  return true;
}

std::vector<DirectionalLight> median_cut(const PixelPowers& pixels, int M) {
  const SummedArea area(pixels);
  std::priority_queue<Rect, std::vector<Rect>, LessPowerful> open;
  std::vector<Rect> done;
  open.push(Rect{0, pixels.width, 0, pixels.height, area.sum(0, pixels.width, 0, pixels.height)});
  // Split the most powerful region until there are M (single pixels and black regions are final).
  while (!open.empty() && open.size() + done.size() < static_cast<std::size_t>(M)) {
    const Rect r = open.top();
    open.pop();
    Rect first{}, second{};
    if (r.weight <= 0.0 || !split(r, area, pixels.width, pixels.height, first, second)) {
      done.push_back(r);
      continue;
    }
    open.push(first);
    open.push(second);
  }
  for (; !open.empty(); open.pop()) done.push_back(open.top());
  // One light per region.
  std::vector<DirectionalLight> lights;
  for (const Rect& r : done) {
    RegionSum region;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) region.add(pixels, x, y, 1.0);
    append_lit(lights, region);
  }
  return lights;
}

// ---- stratified inverse-CDF cells ---------------------------------------------------------------------------

// Overlap of [a0, a1) with cell k of n equal cells of [0, 1); the outer cells extend to infinity so that
// rounding in the cumulative sums cannot lose power.
double cell_overlap(double a0, double a1, int k, int n) {
  const double c0 = k == 0 ? -std::numeric_limits<double>::infinity() : static_cast<double>(k) / n;
  const double c1 = k == n - 1 ? std::numeric_limits<double>::infinity() : static_cast<double>(k + 1) / n;
  return std::max(0.0, std::min(a1, c1) - std::max(a0, c0));
}

// The cells of n that [a0, a1) may overlap: [first, last].
int first_cell(double a0, int n) { return std::clamp(static_cast<int>(std::floor(a0 * n)), 0, n - 1); }
int last_cell(double a1, int n) { return std::clamp(static_cast<int>(std::floor(a1 * n)), 0, n - 1); }

std::vector<DirectionalLight> stratified(const PixelPowers& pixels, int M) {
  int nv = 1;
  for (int d = 1; d * d <= M; ++d)
    if (M % d == 0) nv = d;
  const int nu = M / nv;
  std::vector<double> row_weight(static_cast<std::size_t>(pixels.height), 0.0);
  for (int y = 0; y < pixels.height; ++y)
    for (int x = 0; x < pixels.width; ++x) row_weight[static_cast<std::size_t>(y)] += pixels.weight[pixels.index(x, y)];
  double total = 0.0;
  for (double w : row_weight) total += w;
  std::vector<RegionSum> cells(static_cast<std::size_t>(M));
  if (total <= 0.0) return {};
  // Row y covers [row_cdf, row_cdf + p_y) of the marginal; pixel x covers [pixel_cdf, pixel_cdf + p_x|y) of the
  // row's conditional. A pixel's share of a cell is the product of the two overlap fractions.
  double row_cdf = 0.0;
  for (int y = 0; y < pixels.height; ++y) {
    const double row = row_weight[static_cast<std::size_t>(y)];
    if (row <= 0.0) continue;
    const double p_row = row / total;
    for (int j = first_cell(row_cdf, nv); j <= last_cell(row_cdf + p_row, nv); ++j) {
      const double band_fraction = cell_overlap(row_cdf, row_cdf + p_row, j, nv) / p_row;
      if (band_fraction <= 0.0) continue;
      double pixel_cdf = 0.0;
      for (int x = 0; x < pixels.width; ++x) {
        const double p_pixel = pixels.weight[pixels.index(x, y)] / row;
        if (p_pixel <= 0.0) continue;
        for (int k = first_cell(pixel_cdf, nu); k <= last_cell(pixel_cdf + p_pixel, nu); ++k) {
          const double cell_fraction = cell_overlap(pixel_cdf, pixel_cdf + p_pixel, k, nu) / p_pixel;
          if (cell_fraction > 0.0)
            cells[static_cast<std::size_t>(j * nu + k)].add(pixels, x, y, band_fraction * cell_fraction);
        }
        pixel_cdf += p_pixel;
      }
    }
    row_cdf += p_row;
  }
  std::vector<DirectionalLight> lights;
  for (const RegionSum& cell : cells) append_lit(lights, cell);
  return lights;
}

// ---- k-means on the sphere -----------------------------------------------------------------------------

// Summed-area table of (w, w omega): a rectangle's power and power-weighted direction sum in O(1).
class MomentTable {
 public:
  explicit MomentTable(const PixelPowers& pixels) : stride_(static_cast<std::size_t>(pixels.width) + 1) {
    table_.assign(stride_ * (static_cast<std::size_t>(pixels.height) + 1), glm::dvec4(0.0));
    for (int y = 0; y < pixels.height; ++y)
      for (int x = 0; x < pixels.width; ++x) {
        const double w = pixels.weight[pixels.index(x, y)];
        const glm::dvec4 moment(w, w * pixels.direction(x, y));
        table_[at(x + 1, y + 1)] = moment + table_[at(x, y + 1)] + table_[at(x + 1, y)] - table_[at(x, y)];
      }
  }
  glm::dvec4 sum(int x0, int x1, int y0, int y1) const {
    return table_[at(x1, y1)] - table_[at(x0, y1)] - table_[at(x1, y0)] + table_[at(x0, y0)];
  }
  // The rectangle's k-means cost, sum of w |omega - c|^2 about its centroid c = S / W, which is W - |S|^2 / W.
  double cost(int x0, int x1, int y0, int y1) const {
    const glm::dvec4 m = sum(x0, x1, y0, y1);
    if (m.x <= 0.0) return 0.0;
    return std::max(0.0, m.x - (m.y * m.y + m.z * m.z + m.w * m.w) / m.x);
  }

 private:
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * stride_ + static_cast<std::size_t>(x); }
  std::size_t stride_;
  std::vector<glm::dvec4> table_;
};

struct CostRect {
  int x0, x1, y0, y1;  // pixels [x0, x1) x [y0, y1)
  double cost;
};

struct LessCost {
  bool operator()(const CostRect& a, const CostRect& b) const { return a.cost < b.cost; }
};

// Splits r at the pixel boundary, along u or v, that leaves the least total cost. False for a single pixel.
bool split_least_cost(const CostRect& r, const MomentTable& moments, CostRect& first, CostRect& second) {
  double best = std::numeric_limits<double>::infinity();
  for (int s = r.x0 + 1; s < r.x1; ++s) {
    const double a = moments.cost(r.x0, s, r.y0, r.y1), b = moments.cost(s, r.x1, r.y0, r.y1);
    if (a + b < best) best = a + b, first = {r.x0, s, r.y0, r.y1, a}, second = {s, r.x1, r.y0, r.y1, b};
  }
  for (int s = r.y0 + 1; s < r.y1; ++s) {
    const double a = moments.cost(r.x0, r.x1, r.y0, s), b = moments.cost(r.x0, r.x1, s, r.y1);
    if (a + b < best) best = a + b, first = {r.x0, r.x1, r.y0, s, a}, second = {r.x0, r.x1, s, r.y1, b};
  }
  return best < std::numeric_limits<double>::infinity();
}

// At most M rectangles, cut top-down by splitting the costliest one where the two halves cost least.
std::vector<CostRect> variance_cut_rects(const PixelPowers& pixels, const MomentTable& moments, int M) {
  std::priority_queue<CostRect, std::vector<CostRect>, LessCost> open;
  std::vector<CostRect> done;
  open.push({0, pixels.width, 0, pixels.height, moments.cost(0, pixels.width, 0, pixels.height)});
  while (!open.empty() && open.size() + done.size() < static_cast<std::size_t>(M)) {
    const CostRect r = open.top();
    open.pop();
    CostRect first{}, second{};
    if (r.cost <= 0.0 || !split_least_cost(r, moments, first, second)) {
      done.push_back(r);
      continue;
    }
    open.push(first);
    open.push(second);
  }
  for (; !open.empty(); open.pop()) done.push_back(open.top());
  return done;
}

std::vector<DirectionalLight> variance_cut(const PixelPowers& pixels, int M) {
  std::vector<DirectionalLight> lights;
  for (const CostRect& r : variance_cut_rects(pixels, MomentTable(pixels), M)) {
    RegionSum region;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) region.add(pixels, x, y, 1.0);
    append_lit(lights, region);
  }
  return lights;
}

// Index of the centroid nearest to unit direction d: least |d - c|^2 = 1 - 2 d.c + |c|^2.
std::size_t nearest(const std::vector<glm::dvec3>& centroids, const glm::dvec3& d) {
  std::size_t best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < centroids.size(); ++c) {
    const double distance = glm::dot(centroids[c], centroids[c] - 2.0 * d);
    if (distance < best_distance) best_distance = distance, best = c;
  }
  return best;
}

std::vector<DirectionalLight> k_means(const PixelPowers& pixels, int M) {
  constexpr int kLloydIterations = 10;  // the errors stop improving after about 10 (docs/lights/environment.md)
  // Seeds: the centroids of the variance cut's rectangles that hold power.
  std::vector<glm::dvec3> centroids;
  {
    const MomentTable moments(pixels);
    for (const CostRect& r : variance_cut_rects(pixels, moments, M)) {
      const glm::dvec4 m = moments.sum(r.x0, r.x1, r.y0, r.y1);
      if (m.x > 0.0) centroids.push_back(glm::dvec3(m.y, m.z, m.w) / m.x);
    }
  }
  // Lloyd iterations: give each lit pixel to its nearest centroid, move the centroids to their cells' means.
  for (int iteration = 0; iteration < kLloydIterations; ++iteration) {
    std::vector<glm::dvec4> sums(centroids.size(), glm::dvec4(0.0));
    for (int y = 0; y < pixels.height; ++y)
      for (int x = 0; x < pixels.width; ++x) {
        const double w = pixels.weight[pixels.index(x, y)];
        if (w <= 0.0) continue;
        const glm::dvec3 d = pixels.direction(x, y);
        sums[nearest(centroids, d)] += glm::dvec4(w, w * d);
      }
    for (std::size_t c = 0; c < centroids.size(); ++c)
      if (sums[c].x > 0.0) centroids[c] = glm::dvec3(sums[c].y, sums[c].z, sums[c].w) / sums[c].x;
  }
  // One light per Voronoi cell of the final centroids.
  std::vector<RegionSum> cells(centroids.size());
  for (int y = 0; y < pixels.height; ++y)
    for (int x = 0; x < pixels.width; ++x) {
      if (pixels.weight[pixels.index(x, y)] <= 0.0) continue;
      cells[nearest(centroids, pixels.direction(x, y))].add(pixels, x, y, 1.0);
    }
  std::vector<DirectionalLight> lights;
  for (const RegionSum& cell : cells) append_lit(lights, cell);
  return lights;
}

}  // namespace

std::vector<DirectionalLight> environment_to_directional_lights(const EnvironmentMap& map, int M,
                                                                EnvironmentSampling sampling) {
  if (M < 1) throw Error(fmt::format("{}: cannot make {} directional lights; M must be at least 1", map.source, M));
  const PixelPowers pixels(map);
  switch (sampling) {
    case EnvironmentSampling::MedianCut:
      return median_cut(pixels, M);
    case EnvironmentSampling::Stratified:
      return stratified(pixels, M);
    case EnvironmentSampling::VarianceCut:
      return variance_cut(pixels, M);
    case EnvironmentSampling::KMeans:
      break;
  }
  return k_means(pixels, M);
}

}  // namespace lucent
