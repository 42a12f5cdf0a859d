// random_walk_io.h: the random-walk method's own GPU data (C++ and GLSL): the triangle BVH and the triangles it
// indexes (std430 storage buffers), built on the CPU (triangle_bvh.h).
#ifndef LUCENT_METHODS_RANDOM_WALK_IO_H
#define LUCENT_METHODS_RANDOM_WALK_IO_H
#include "shared/shader_io.h"

LUCENT_SHADER_BEGIN

// One node of the flattened BVH, depth-first: an interior node's left child is the next node (index + 1).
// The integer fields are stored as float bits (intBitsToFloat / floatBitsToInt in GLSL, std::bit_cast in C++).
struct BvhNodeGPU {
  vec4 lower;  // xyz: box minimum [scene units]; w: leaf: index of its first triangle; interior: right child's index
  vec4 upper;  // xyz: box maximum [scene units]; w: triangle count (0: interior node)
};

// One world-space triangle, in the BVH's leaf order.
struct TriangleGPU {
  vec4 p0;  // xyz: corner 0 [scene units]; w: the scene object's index (float bits)
  vec4 e1;  // xyz: corner 1 - corner 0; w: 0
  vec4 e2;  // xyz: corner 2 - corner 0; w: 0
  vec4 n0;  // xyz: unit shading normal at corner 0; w: the triangle's index before the BVH reordered them
            // (float bits)
  vec4 n1;  // xyz: unit shading normal at corner 1; w: 0
  vec4 n2;  // xyz: unit shading normal at corner 2; w: 0
};

LUCENT_SHADER_END

#if defined(__cplusplus)
#include <cstddef>
static_assert(sizeof(lucent::shader::BvhNodeGPU) == 32);
static_assert(offsetof(lucent::shader::BvhNodeGPU, upper) == 16);
static_assert(sizeof(lucent::shader::TriangleGPU) == 96);
static_assert(offsetof(lucent::shader::TriangleGPU, n0) == 48);
static_assert(offsetof(lucent::shader::TriangleGPU, n2) == 80);
#endif

#endif
