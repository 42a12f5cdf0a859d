// atlas_packing.cpp: see atlas_packing.h.
#include "texture_space/atlas_packing.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>

namespace lucent::texture_space {
namespace {

// A chart at one scale and quarter turn: corners in its own texel frame (their minimum at (0.5, 0.5)), and per
// texel row the spans of texels its triangles can touch (inclusive x ranges, left to right; gaps of at most
// 2 border texels, too narrow for any other chart, are closed), with the widest span of each row.
struct Mask {
  std::vector<glm::dvec2> corners;
  int width = 0, height = 0;
  std::vector<glm::ivec2> spans;
  std::vector<std::size_t> first;  // row r's spans are spans[first[r] .. first[r + 1])
  std::vector<int> widest;         // per row, the widest span's length minus one (-1: an empty row)
  std::vector<int> rows_by_width;  // the non-empty rows, widest first (the likeliest to be blocked)
  std::vector<std::size_t> spans_by_length;  // span indices, longest first
  std::vector<int> span_row;                 // the row of each span
};

glm::dvec2 turn(glm::dvec2 p, int quarter_turns) {
  for (int i = 0; i < quarter_turns; ++i) p = {-p.y, p.x};  // exact in floating point
  return p;
}

Mask rasterise(const std::vector<glm::dvec2>& chart, double scale, int quarter_turns, int border) {
  Mask m;
  m.corners.reserve(chart.size());
  glm::dvec2 lo(1e300);
  for (glm::dvec2 p : chart) {
    m.corners.push_back(turn(p * scale, quarter_turns));
    lo = glm::min(lo, m.corners.back());
  }
  for (glm::dvec2& p : m.corners) p += glm::dvec2(0.5) - lo;
  // Each triangle's texel box, then its x range in each of its rows, bucketed by row and sorted by start.
  std::vector<glm::ivec2> boxes;
  boxes.reserve(2 * (chart.size() / 3));
  glm::ivec2 extent(0);
  for (std::size_t t = 0; t + 2 < m.corners.size(); t += 3) {
    glm::ivec2 a, b;
    triangle_texel_box(m.corners[t], m.corners[t + 1], m.corners[t + 2], a, b);
    a = glm::max(a, glm::ivec2(0));  // the corners are >= 0.5, so only the 1e-3 widening could reach below 0
    boxes.push_back(a), boxes.push_back(b);
    extent = glm::max(extent, b + 1);
  }
  m.width = extent.x, m.height = extent.y;
  std::vector<std::size_t> start(static_cast<std::size_t>(m.height) + 1, 0);
  for (std::size_t i = 0; i < boxes.size(); i += 2)
    for (int y = boxes[i].y; y <= boxes[i + 1].y; ++y) ++start[static_cast<std::size_t>(y) + 1];
  for (std::size_t r = 1; r < start.size(); ++r) start[r] += start[r - 1];
  std::vector<glm::ivec2> pieces(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < boxes.size(); i += 2)
    for (int y = boxes[i].y; y <= boxes[i + 1].y; ++y) pieces[fill[static_cast<std::size_t>(y)]++] = {boxes[i].x, boxes[i + 1].x};
  m.first.assign(static_cast<std::size_t>(m.height) + 1, 0);
  m.widest.assign(static_cast<std::size_t>(m.height), -1);
  for (int row = 0; row < m.height; ++row) {
    const auto begin = pieces.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(row)]);
    const auto end = pieces.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(row) + 1]);
    std::sort(begin, end, [](glm::ivec2 u, glm::ivec2 v) { return u.x < v.x; });
    for (auto piece = begin; piece != end; ++piece) {
      if (piece != begin && piece->x <= m.spans.back().y + 2 * border + 1)
        m.spans.back().y = std::max(m.spans.back().y, piece->y);
      else
        m.spans.push_back(*piece);
    }
    m.first[static_cast<std::size_t>(row) + 1] = m.spans.size();
    for (std::size_t i = m.first[static_cast<std::size_t>(row)]; i < m.spans.size(); ++i)
      m.widest[static_cast<std::size_t>(row)] = std::max(m.widest[static_cast<std::size_t>(row)], m.spans[i].y - m.spans[i].x);
    if (m.widest[static_cast<std::size_t>(row)] >= 0) m.rows_by_width.push_back(row);
  }
  std::stable_sort(m.rows_by_width.begin(), m.rows_by_width.end(),
                   [&](int a, int b) { return m.widest[static_cast<std::size_t>(a)] > m.widest[static_cast<std::size_t>(b)]; });
  m.span_row.resize(m.spans.size());
  for (int row = 0; row < m.height; ++row)
    for (std::size_t i = m.first[static_cast<std::size_t>(row)]; i < m.first[static_cast<std::size_t>(row) + 1]; ++i) m.span_row[i] = row;
  m.spans_by_length.resize(m.spans.size());
  std::iota(m.spans_by_length.begin(), m.spans_by_length.end(), std::size_t{0});
  std::stable_sort(m.spans_by_length.begin(), m.spans_by_length.end(), [&](std::size_t a, std::size_t b) {
    return m.spans[a].y - m.spans[a].x > m.spans[b].y - m.spans[b].x;
  });
  return m;
}

// Texels taken by placed charts, grown by the border: per row, the length of the free run starting at each texel
// and the next free texel at or right of it, and the longest free run of the row.
class Occupancy {
 public:
  explicit Occupancy(int size)
      : size_(size), taken_(cells(), 0), run_(cells(), 0), next_free_(cells(), 0), longest_(static_cast<std::size_t>(size), 0) {
    for (int y = 0; y < size; ++y) update_row(y);
  }

  // The lowest row (then leftmost texel) where every span of the mask lies on free texels; false when there is
  // none with the mask's top at most `below` (a row count).
  bool find(const Mask& m, int below, int& out_x, int& out_y) const {
    std::size_t hint = 0;
    for (int y = 0; y + m.height <= std::min(size_, below); ++y) {
      bool possible = true;
      for (std::size_t i = 0; i < m.rows_by_width.size() && possible; ++i) {
        const int r = m.rows_by_width[i];
        possible = longest_[static_cast<std::size_t>(y + r)] > m.widest[static_cast<std::size_t>(r)];
      }
      if (!possible) continue;
      for (int x = 0; x + m.width <= size_;) {
        const int next = blocked_until(m, x, y, hint);
        if (next == x) {
          out_x = x, out_y = y;
          return true;
        }
        x = next;
      }
    }
    return false;
  }

  // Marks the mask at (x, y) grown by `border` texels as taken.
  void take(const Mask& m, int x, int y, int border) {
    for (int r = 0; r < m.height; ++r)
      for (std::size_t i = m.first[static_cast<std::size_t>(r)]; i < m.first[static_cast<std::size_t>(r) + 1]; ++i) {
        const int x0 = std::max(0, x + m.spans[i].x - border), x1 = std::min(size_ - 1, x + m.spans[i].y + border);
        for (int row = std::max(0, y + r - border); row <= std::min(size_ - 1, y + r + border); ++row)
          std::fill(taken_.begin() + static_cast<std::ptrdiff_t>(index(x0, row)),
                    taken_.begin() + static_cast<std::ptrdiff_t>(index(x1, row)) + 1, 1);
      }
    for (int row = std::max(0, y - border); row <= std::min(size_ - 1, y + m.height - 1 + border); ++row) update_row(row);
  }

 private:
  std::size_t cells() const { return static_cast<std::size_t>(size_) * static_cast<std::size_t>(size_); }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * static_cast<std::size_t>(size_) + static_cast<std::size_t>(x); }

  // x when the mask fits at (x, y), else an x' > x below which it cannot fit either: a blocked span's start moved
  // to the next free texel after the taken one that ends its free run. The span that blocked last (`hint`, an index
  // into spans_by_length) is tried first, as it tends to block again at the next x; which blocked span answers
  // changes how far the scan jumps, never where the mask first fits.
  int blocked_until(const Mask& m, int x, int y, std::size_t& hint) const {
    const std::size_t count = m.spans_by_length.size();
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t order = k == 0 ? hint : (k <= hint ? k - 1 : k);
      const std::size_t i = m.spans_by_length[order];
      const int l = m.spans[i].x, rr = m.spans[i].y, row = y + m.span_row[i];
      const std::size_t at = index(x + l, row);
      if (run_[at] > rr - l) continue;
      hint = order;
      const int taken = x + l + run_[at];
      const int free = taken >= size_ ? size_ : next_free_[index(taken, row)];
      return free - l;
    }
    return x;
  }

  void update_row(int y) {
    int run = 0, next_free = size_, longest = 0;
    for (int x = size_ - 1; x >= 0; --x) {
      const std::size_t i = index(x, y);
      run = taken_[i] ? 0 : run + 1;
      if (!taken_[i]) next_free = x;
      run_[i] = run, next_free_[i] = next_free;
      longest = std::max(longest, run);
    }
    longest_[static_cast<std::size_t>(y)] = longest;
  }

  int size_;
  std::vector<unsigned char> taken_;
  std::vector<int> run_, next_free_, longest_;
};

// Packs at one scale; false when a chart finds no place.
bool pack_at(const std::vector<std::vector<glm::dvec2>>& charts, int size, int border, double scale,
             std::vector<std::vector<glm::dvec2>>& texels) {
  Occupancy occupancy(size);
  texels.resize(charts.size());
  for (std::size_t k = 0; k < charts.size(); ++k) {
    int best_x = -1, best_y = size;
    Mask best;
    for (int quarter_turns = 0; quarter_turns < 4; ++quarter_turns) {
      Mask m = rasterise(charts[k], scale, quarter_turns, border);
      int x = 0, y = 0;
      // Only a placement as low as the best so far is of interest (then the leftmost).
      if (m.width > size || !occupancy.find(m, best_y + m.height, x, y)) continue;
      if (y < best_y || (y == best_y && x < best_x)) best_x = x, best_y = y, best = std::move(m);
    }
    if (best_x < 0) return false;
    occupancy.take(best, best_x, best_y, border);
    texels[k] = std::move(best.corners);
    for (glm::dvec2& p : texels[k]) p += glm::dvec2(best_x, best_y);
  }
  return true;
}

}  // namespace

void triangle_texel_box(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::ivec2& lo, glm::ivec2& hi) {
  constexpr double kWiden = 1e-3;
  glm::dvec2 min = glm::min(a, glm::min(b, c)) - kWiden, max = glm::max(a, glm::max(b, c)) + kWiden;
  lo = glm::ivec2(glm::ceil(min)) - 1;
  hi = glm::ivec2(glm::floor(max));
}

double pack_charts(const std::vector<std::vector<glm::dvec2>>& charts, int size, int border,
                   std::vector<std::vector<glm::dvec2>>& texels) {
  // The charts' own area bounds the scale from above (all texels covered), and so does their longest side.
  double area = 0.0, longest = 0.0;
  for (const std::vector<glm::dvec2>& chart : charts) {
    glm::dvec2 lo(1e300), hi(-1e300);
    for (std::size_t t = 0; t + 2 < chart.size(); t += 3) {
      area += 0.5 * std::abs((chart[t + 1].x - chart[t].x) * (chart[t + 2].y - chart[t].y) -
                             (chart[t + 1].y - chart[t].y) * (chart[t + 2].x - chart[t].x));
      for (int i = 0; i < 3; ++i) lo = glm::min(lo, chart[t + i]), hi = glm::max(hi, chart[t + i]);
    }
    if (!chart.empty()) longest = std::max(longest, std::max(hi.x - lo.x, hi.y - lo.y));
  }
  double hi = size / std::max(1e-300, std::sqrt(area));
  if (longest > 0.0) hi = std::min(hi, size / longest);
  // Down by factors of 0.7 to a scale that fits (at the smallest, every chart is about one texel), then bisect
  // (geometrically) until the scale is known to 0.2%.
  double lo = hi;
  std::vector<std::vector<glm::dvec2>> trial;
  for (int i = 0;; ++i) {
    lo *= 0.7;
    if (pack_at(charts, size, border, lo, texels)) break;
    if (lo * longest < 1e-3 || i == 200) return 0.0;  // every chart already within one texel
    hi = lo;
  }
  while (hi / lo > 1.002) {
    const double mid = std::sqrt(lo * hi);
    if (pack_at(charts, size, border, mid, trial)) {
      lo = mid;
      texels.swap(trial);
    } else {
      hi = mid;
    }
  }
  return lo;
}

}  // namespace lucent::texture_space
