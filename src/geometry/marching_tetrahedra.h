// marching_tetrahedra.h: the per-cell logic of isosurface extraction by marching tetrahedra, shared by the
// compute shaders (shaders/geometry/) and the CPU reference (geometry/isosurface_cpu.cpp).
//
// Method: each grid cell is split into the 6 Kuhn (Freudenthal) tetrahedra around its main diagonal,
// corners 0 -> e_a -> e_a + e_b -> (1,1,1) for the 6 axis orders (a, b, c). All cells are split the same way,
// so neighbouring cells split their shared face along the same diagonal and the tetrahedra form a conforming
// mesh of the box. The field is interpolated linearly on each tetrahedron; its zero set there is one
// triangle or one planar quad (2 triangles), and the union over the grid is a closed 2-manifold whenever
// the boundary samples are outside (Doi & Koide 1991, "An efficient method of triangulating
// equi-valued surfaces by using tetrahedral cells"; no case table, no ambiguous cases).
//
// Edges: every edge of this tetrahedral mesh goes from a grid point p to p + d with d in {0,1}^3 \ {0}
// (7 directions, direction index = x + 2y + 4z - 1). The edge belongs to its lower end point p, and its
// vertex is computed once there, from the two samples in that order; triangles refer to it by index, so
// shared vertices are identical by construction.
//
// Inside is f > 0 (strictly); f = 0 counts as outside.
#ifndef LUCENT_GEOMETRY_MARCHING_TETRAHEDRA_H
#define LUCENT_GEOMETRY_MARCHING_TETRAHEDRA_H
#include "shared/bridge.h"

#define LUCENT_MT_DIRECTIONS 7       // edge directions owned by a grid point
#define LUCENT_MT_TETS_PER_CELL 6

LUCENT_SHADER_BEGIN

// Vertices are kept at least this fraction of an edge away from its end points, so that two edges never
// produce the same vertex and no triangle has zero area (a sample at exactly f = 0 would otherwise put the
// vertices of all its crossing edges on the sample).
LUCENT_CONST float kMtMinEdgeFraction = 1.0e-3f;

LUCENT_INLINE bool mt_inside(float f) { return f > 0.0f; }

// Offset of cube corner `code` (bit 0: +x, bit 1: +y, bit 2: +z).
LUCENT_INLINE ivec3 mt_corner_offset(int code) { return ivec3(code & 1, (code >> 1) & 1, (code >> 2) & 1); }

// Corner k (0..3) of Kuhn tetrahedron `tet` (0..5) as a cube corner code. Axis orders (a, b, c):
// 0: xyz, 1: xzy, 2: yxz, 3: yzx, 4: zxy, 5: zyx. Corner codes grow along the tetrahedron (each contains
// the previous one's bits), so corner j < k is the lower end of edge (j, k).
LUCENT_INLINE int mt_tet_corner(int tet, int k) {
  if (k == 0) return 0;
  if (k == 3) return 7;
  int a = tet / 2;
  int b = (tet == 2 || tet == 4) ? 0 : ((tet == 0 || tet == 5) ? 1 : 2);
  return k == 1 ? (1 << a) : ((1 << a) | (1 << b));
}

// Orientation of tetrahedron `tet`: sign of det(v1 - v0, v2 - v0, v3 - v0) = sign of its axis order.
LUCENT_INLINE int mt_tet_parity(int tet) { return (tet == 0 || tet == 3 || tet == 4) ? 1 : -1; }

// Bit k of the result: corner k of tetrahedron `tet` is inside (cube_inside: bit c for cube corner c).
LUCENT_INLINE int mt_tet_inside_mask(int tet, int cube_inside) {
  int mask = 0;
  for (int k = 0; k < 4; ++k)
    if (((cube_inside >> mt_tet_corner(tet, k)) & 1) != 0) mask |= 1 << k;
  return mask;
}

// Number of triangles of a tetrahedron with the given inside mask: 0, 1 or 2.
LUCENT_INLINE int mt_tet_triangle_count(int inside_mask) {
  int n = bitCount(uint(inside_mask));
  return (n == 0 || n == 4) ? 0 : (n == 2 ? 2 : 1);
}

// An even permutation (a, b, c, d) of the corners (0, 1, 2, 3) that puts the lone corner first (one corner
// differs from the others) or the two inside corners first (two inside). Even, so det(b-a, c-a, d-a) keeps
// the sign of mt_tet_parity.
LUCENT_INLINE ivec4 mt_case_order(int inside_mask) {
  int m = (bitCount(uint(inside_mask)) == 3) ? (15 ^ inside_mask) : inside_mask;
  if (m == 2) return ivec4(1, 0, 3, 2);
  if (m == 4) return ivec4(2, 3, 0, 1);
  if (m == 8) return ivec4(3, 2, 1, 0);
  if (m == 12) return ivec4(2, 3, 0, 1);
  if (m == 5) return ivec4(0, 2, 3, 1);
  if (m == 10) return ivec4(1, 3, 2, 0);
  if (m == 9) return ivec4(0, 3, 1, 2);
  if (m == 6) return ivec4(1, 2, 0, 3);
  return ivec4(0, 1, 2, 3);  // m == 1 or m == 3
}

// Edge (j, k) of a tetrahedron encoded as 4 * lower + upper corner index.
LUCENT_INLINE int mt_edge(int j, int k) { return j < k ? 4 * j + k : 4 * k + j; }

// Triangle `triangle` (0 or 1) of a tetrahedron: its three vertices as mt_edge codes, counter-clockwise seen
// from outside (the normal (v1 - v0) x (v2 - v0) points toward f < 0).
// One corner a apart from b, c, d: the triangle on edges ab, ac, ad; its normal points away from a when
// det(b-a, c-a, d-a) > 0, which is outward when a is the inside one. Two inside corners a, b: the quad
// ac, ad, bd, bc (consecutive vertices share a face of the tetrahedron), split along ac-bd, which lies
// inside the tetrahedron and so belongs to no other triangle.
LUCENT_INLINE ivec3 mt_tet_triangle(int inside_mask, int parity, int triangle) {
  ivec4 o = mt_case_order(inside_mask);
  int n = bitCount(uint(inside_mask));
  if (n == 2) {
    int ac = mt_edge(o.x, o.z), ad = mt_edge(o.x, o.w), bd = mt_edge(o.y, o.w), bc = mt_edge(o.y, o.z);
    if (parity > 0) return triangle == 0 ? ivec3(ac, ad, bd) : ivec3(ac, bd, bc);
    return triangle == 0 ? ivec3(ac, bd, ad) : ivec3(ac, bc, bd);
  }
  int ab = mt_edge(o.x, o.y), ac = mt_edge(o.x, o.z), ad = mt_edge(o.x, o.w);
  bool away_from_a = (n == 1) == (parity > 0);
  return away_from_a ? ivec3(ab, ac, ad) : ivec3(ab, ad, ac);
}

// Number of triangles of the cell whose corners have the given inside bits (bit c: cube corner c).
LUCENT_INLINE int mt_cell_triangle_count(int cube_inside) {
  int count = 0;
  for (int tet = 0; tet < LUCENT_MT_TETS_PER_CELL; ++tet)
    count += mt_tet_triangle_count(mt_tet_inside_mask(tet, cube_inside));
  return count;
}

// Bit (direction - 1) of the result: the edge from grid point `point` to point + offset(direction) lies in
// the grid (points 0..cells per axis) and crosses the surface. f_corner0 is the point's sample, f_other the
// sample at point + offset(direction).
LUCENT_INLINE uint mt_edge_bit(ivec3 point, ivec3 cells, int direction, float f_corner0, float f_other) {
  ivec3 end = point + mt_corner_offset(direction);
  bool in_grid = end.x <= cells.x && end.y <= cells.y && end.z <= cells.z;
  bool crosses = mt_inside(f_corner0) != mt_inside(f_other);
  return (in_grid && crosses) ? (1u << uint(direction - 1)) : 0u;
}

// Index of the vertex of edge `direction` (1..7) among the crossing edges of a point: the vertices of a
// point are stored in direction order after the point's first vertex.
LUCENT_INLINE uint mt_vertex_rank(uint edge_mask, int direction) {
  return uint(bitCount(edge_mask & ((1u << uint(direction - 1)) - 1u)));
}

// Fraction along an edge (from its lower end, sample f_lower, to its upper end, f_upper; the signs differ)
// where the linear interpolant is zero, kept kMtMinEdgeFraction away from the ends.
LUCENT_INLINE float mt_edge_fraction(float f_lower, float f_upper) {
  return clamp(f_lower / (f_lower - f_upper), kMtMinEdgeFraction, 1.0f - kMtMinEdgeFraction);
}

// World position of grid point `point` [scene units].
LUCENT_INLINE vec3 mt_grid_position(vec3 lower, vec3 spacing, ivec3 point) { return lower + vec3(point) * spacing; }

// The sample stored for a grid point: points on the grid's outer faces are forced outside, so the
// surface is closed even where a body would reach the box (it is then capped just inside the box).
LUCENT_INLINE float mt_stored_sample(float f, ivec3 point, ivec3 cells) {
  bool on_boundary = point.x == 0 || point.y == 0 || point.z == 0 || point.x == cells.x || point.y == cells.y ||
                     point.z == cells.z;
  return on_boundary ? min(f, 0.0f) : f;
}

LUCENT_SHADER_END

#endif
