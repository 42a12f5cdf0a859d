// distance_grid.cpp: the random-walk method's distance grid (see distance_grid.h).
#include "methods/random_walk/distance_grid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent::methods::random_walk {

DistanceGrid build_distance_grid(const TriangleBvh& bvh, glm::vec3 lower, glm::vec3 upper,
                                 const DistanceGridOptions& options) {
  if (options.max_cells_per_axis < 1 || options.max_cells_per_axis > 1024)
    throw Error(fmt::format("distance grid: {} cells per axis, outside [1, 1024]", options.max_cells_per_axis));
  if (!(options.margin >= 0.0f))
    throw Error(fmt::format("distance grid: negative margin {}", options.margin));
  DistanceGrid grid;
  if (bvh.nodes.empty() || !(lower.x <= upper.x && lower.y <= upper.y && lower.z <= upper.z)) return grid;
  const glm::vec3 extent = upper - lower;
  const float longest = std::max({extent.x, extent.y, extent.z, 1e-6f * std::max(1.0f, glm::length(lower))});
  const float margin = options.margin * longest;
  grid.cell_size = (longest + 2.0f * margin) / static_cast<float>(options.max_cells_per_axis);
  for (int a = 0; a < 3; ++a)
    grid.cells[a] = std::clamp(static_cast<int>(std::ceil((extent[a] + 2.0f * margin) / grid.cell_size)), 1,
                               options.max_cells_per_axis);
  grid.origin = 0.5f * (lower + upper) - 0.5f * grid.cell_size * glm::vec3(grid.cells);
  grid.distances.resize(static_cast<std::size_t>(grid.cells.x) * static_cast<std::size_t>(grid.cells.y) *
                        static_cast<std::size_t>(grid.cells.z));
  // Neighbouring centres mostly share their nearest triangle: the previous one's (along the row, or the row
  // before's first at a row's start) starts each search with a radius close to the answer. Each z layer starts
  // afresh, so the layers are independent: threads take them in turn, and the result does not depend on how many.
  auto fill_layer = [&](int z) {
    std::size_t i = static_cast<std::size_t>(z) * static_cast<std::size_t>(grid.cells.x) *
                    static_cast<std::size_t>(grid.cells.y);
    std::uint32_t row_guess = kNoTriangle;
    for (int y = 0; y < grid.cells.y; ++y) {
      std::uint32_t guess = row_guess;
      for (int x = 0; x < grid.cells.x; ++x, ++i) {
        const std::optional<NearestTriangle> nearest =
            bvh.nearest_triangle(grid.cell_centre({x, y, z}), std::numeric_limits<float>::infinity(), guess);
        grid.distances[i] = nearest->distance;  // never empty: the tree has triangles and no bound
        guess = nearest->triangle;
        if (x == 0) row_guess = guess;
      }
    }
  };
  const int threads = std::clamp(options.threads > 0 ? options.threads
                                                     : static_cast<int>(std::thread::hardware_concurrency()),
                                 1, std::min(64, grid.cells.z));
  std::atomic<int> next_layer{0};
  auto work = [&] {
    for (int z = next_layer++; z < grid.cells.z; z = next_layer++) fill_layer(z);
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) {
    try {
      workers.emplace_back(work);
    } catch (const std::system_error&) {  // no more threads to be had: those started (and this one) do it all
      break;
    }
  }
  work();
  for (std::thread& w : workers) w.join();
  return grid;
}

float DistanceGrid::lower_bound_distance(glm::vec3 p) const {
  if (distances.empty() || !std::isfinite(p.x + p.y + p.z)) return 0.0f;
  // Clamped as floats before the conversion, so that far points convert in range.
  const glm::ivec3 cell(glm::clamp(glm::floor((p - origin) / cell_size), glm::vec3(0.0f), glm::vec3(cells - 1)));
  const std::size_t i = static_cast<std::size_t>(cell.x) +
                        static_cast<std::size_t>(cells.x) *
                            (static_cast<std::size_t>(cell.y) + static_cast<std::size_t>(cells.y) * static_cast<std::size_t>(cell.z));
  return std::max(0.0f, distances[i] - glm::length(p - cell_centre(cell)));
}

}  // namespace lucent::methods::random_walk
