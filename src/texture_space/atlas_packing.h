// atlas_packing.h: packing of charts by their own shapes into a square texture with one global scale.
//
// At a trial scale every chart is rasterised in four quarter turns into a texel mask: per texel row, the spans of
// texels whose square one of its triangles can touch (the union of the triangles' texel bounding boxes; a gap of
// at most 2 border texels inside a row, too narrow for another chart, counts as taken). Charts go in the caller's
// order (largest first packs best); each goes to the turn and integer texel offset that is lowest, then leftmost,
// where every span lies on free texels of an occupancy bitmap (first fit, scanned bottom-up, left to right), so
// ragged charts interlock and small ones fill the holes left in and between large ones. A placed mask is marked in
// the bitmap grown by `border` texels on every side (square neighbourhood), so at least `border` empty texels
// separate the texels of any two charts. Free runs per row (their length from each texel, the next free texel,
// the longest run of the row) let the scan skip taken texels and rows. The largest scale that fits is found by
// steps of 0.7 down from the bound the charts' area sets, then geometric bisection to 0.2%.
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace lucent::texture_space {

// `charts[k]` holds chart k's triangles, three corners each, in its plane [scene units]. On success fills
// `texels[k]` with the corners' positions in the size x size texture [texels, (0, 0) the lower-left corner of
// texel (0, 0)], each chart turned by a multiple of 90 degrees (orientation kept) and moved by a texel offset, and
// returns the scale [texels per scene unit]; returns 0 when the charts do not fit even at one texel each.
double pack_charts(const std::vector<std::vector<glm::dvec2>>& charts, int size, int border,
                   std::vector<std::vector<glm::dvec2>>& texels);

// The texels whose square a triangle with corners a, b, c [texels] can touch: x from ceil(min x) - 1 to
// floor(max x) (and likewise y), widened by 1e-3 texel so that rounding the corners to float texture coordinates
// cannot touch a texel outside. Inclusive bounds.
void triangle_texel_box(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::ivec2& lo, glm::ivec2& hi);

}  // namespace lucent::texture_space
