// dilate.cpp: see dilate.h.
#include "texture_space/dilate.h"

namespace lucent::texture_space {

void dilate(std::vector<glm::vec4>& values, int size, int texels) {
  static constexpr int kOffsets[8][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  std::vector<glm::vec4> next;
  for (int step = 0; step < texels; ++step) {
    next = values;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (values[static_cast<std::size_t>(y * size + x)].w != 0.0f) continue;
        for (const auto& o : kOffsets) {
          int nx = x + o[0], ny = y + o[1];
          if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
          const glm::vec4& neighbour = values[static_cast<std::size_t>(ny * size + nx)];
          if (neighbour.w == 0.0f) continue;
          next[static_cast<std::size_t>(y * size + x)] = neighbour;
          break;
        }
      }
    values.swap(next);
  }
}

}  // namespace lucent::texture_space
