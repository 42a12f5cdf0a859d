// atlas_packing.h: skyline (bottom-left) packing of chart bounding boxes into a square texture with one global
// scale.
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace lucent::texture_space {

struct PackedBox {
  glm::dvec2 origin{0.0};  // where the box's lower corner lands [texels]
};

// Places boxes of `extents` [scene units] (in the given order, each where its top ends lowest; tallest first packs
// best) into a size x size texture at the largest scale [texels per scene
// unit] that fits, with at least `gap` texels between boxes and gap / 2 to the texture's edges. Returns the
// scale, or 0 when even the smallest scale does not fit.
double pack_boxes(const std::vector<glm::dvec2>& extents, int size, int gap, std::vector<PackedBox>& out);

}  // namespace lucent::texture_space
