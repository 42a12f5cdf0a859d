// procedural_shapes.cpp: sphere, torus, box, plane and lathe meshes centred at the origin, y up. Every triangle is
// counter-clockwise seen from outside: cross(p1 - p0, p2 - p0) points along the outward normal.
// Texture coordinates lie in [0, 1]^2 and no two triangles overlap there. Where the parametrisation wraps
// (the seam of a revolved surface, the poles), the vertex is duplicated with a copy of its position and normal
// (bit for bit, so the rendered surface is the same as with one shared vertex) and its own texture coordinates.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "lucent/mesh.h"

namespace lucent {
namespace {

void add_vertex(TriangleMesh& mesh, glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(n);
  mesh.uvs.push_back(uv);
}

// A copy of vertex i (position and normal) with other texture coordinates: the far side of a seam.
void add_seam_copy(TriangleMesh& mesh, std::uint32_t i, glm::vec2 uv) {
  add_vertex(mesh, mesh.positions[i], mesh.normals[i], uv);
}

void add_triangle(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// Quad of a parametric grid: a = (row, col), b = (row, col + 1), c = (row + 1, col), d = (row + 1, col + 1),
// where cross(d/dcol, d/drow) points out of the surface.
void add_quad(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  add_triangle(mesh, a, b, c);
  add_triangle(mesh, b, d, c);
}

// A flat rectangle spanning center +- u +- v with unit normal n, which must point along cross(u, v). Its texture
// coordinates fill the rectangle uv_lower..uv_upper, the first along u.
void add_face(TriangleMesh& mesh, glm::vec3 center, glm::vec3 u, glm::vec3 v, glm::vec3 n,
              glm::vec2 uv_lower = glm::vec2(0.0f), glm::vec2 uv_upper = glm::vec2(1.0f)) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  add_vertex(mesh, center - u - v, n, uv_lower);
  add_vertex(mesh, center + u - v, n, {uv_upper.x, uv_lower.y});
  add_vertex(mesh, center + u + v, n, uv_upper);
  add_vertex(mesh, center - u + v, n, {uv_lower.x, uv_upper.y});
  add_triangle(mesh, base, base + 1, base + 2);
  add_triangle(mesh, base, base + 2, base + 3);
}

float fraction(int i, int n) { return static_cast<float>(i) / static_cast<float>(n); }

std::uint32_t u32(int i) { return static_cast<std::uint32_t>(i); }

}  // namespace

// rings: latitude bands from pole to pole (at least 2); segments: divisions around the y axis (at least 3).
// The poles are closed by triangle fans, so the mesh is watertight (welded by position).
// Texture coordinates: u = phi / 2 pi (longitude, the seam at phi = 0 duplicated), v = 1 at the north pole to 0
// at the south pole; each pole has one vertex per segment, at the middle of the segment's u range.
TriangleMesh make_sphere(float radius, int rings, int segments) {
  rings = std::max(rings, 2);
  segments = std::max(segments, 3);
  TriangleMesh mesh;
  for (int s = 0; s < segments; ++s)
    add_vertex(mesh, {0.0f, radius, 0.0f}, {0.0f, 1.0f, 0.0f}, {fraction(2 * s + 1, 2 * segments), 1.0f});
  for (int r = 1; r < rings; ++r) {
    float theta = glm::pi<float>() * fraction(r, rings);
    const auto first = u32(static_cast<int>(mesh.positions.size()));
    for (int s = 0; s < segments; ++s) {
      float phi = glm::two_pi<float>() * fraction(s, segments);
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      add_vertex(mesh, radius * n, n, {fraction(s, segments), 1.0f - fraction(r, rings)});
    }
    add_seam_copy(mesh, first, {1.0f, 1.0f - fraction(r, rings)});
  }
  const auto south_first = u32(static_cast<int>(mesh.positions.size()));
  for (int s = 0; s < segments; ++s)
    add_vertex(mesh, {0.0f, -radius, 0.0f}, {0.0f, -1.0f, 0.0f}, {fraction(2 * s + 1, 2 * segments), 0.0f});

  auto north = [&](int s) { return u32(s); };
  auto south = [&](int s) { return south_first + u32(s); };
  auto ring_vertex = [&](int r, int s) { return u32(segments + (r - 1) * (segments + 1) + s); };
  for (int s = 0; s < segments; ++s) {
    add_triangle(mesh, north(s), ring_vertex(1, s + 1), ring_vertex(1, s));
    for (int r = 1; r < rings - 1; ++r) {
      add_quad(mesh, ring_vertex(r, s), ring_vertex(r, s + 1),  //
               ring_vertex(r + 1, s), ring_vertex(r + 1, s + 1));
    }
    add_triangle(mesh, ring_vertex(rings - 1, s), ring_vertex(rings - 1, s + 1), south(s));
  }
  return mesh;
}

// The tube's centre circle has radius major_radius in the xz plane. rings: cross-sections around the y axis
// (at least 3); segments: divisions around each cross-section (at least 3).
// Texture coordinates: u = r / rings around the y axis, v = s / segments around the tube; both seams duplicated
// (a grid of (rings + 1) x (segments + 1) vertices).
TriangleMesh make_torus(float major_radius, float minor_radius, int rings, int segments) {
  rings = std::max(rings, 3);
  segments = std::max(segments, 3);
  TriangleMesh mesh;
  auto vertex = [&](int r, int s) { return u32(r * (segments + 1) + s); };
  for (int r = 0; r <= rings; ++r) {
    if (r == rings) {  // the seam: the first cross-section again
      for (int s = 0; s <= segments; ++s) add_seam_copy(mesh, vertex(0, s), {1.0f, fraction(s, segments)});
      break;
    }
    float u = glm::two_pi<float>() * fraction(r, rings);
    glm::vec3 radial(std::cos(u), 0.0f, std::sin(u));
    for (int s = 0; s < segments; ++s) {
      float v = glm::two_pi<float>() * fraction(s, segments);
      glm::vec3 n = std::cos(v) * radial + glm::vec3(0.0f, std::sin(v), 0.0f);
      add_vertex(mesh, major_radius * radial + minor_radius * n, n, {fraction(r, rings), fraction(s, segments)});
    }
    add_seam_copy(mesh, vertex(r, 0), {fraction(r, rings), 1.0f});
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      add_quad(mesh, vertex(r, s), vertex(r, s + 1), vertex(r + 1, s), vertex(r + 1, s + 1));
  return mesh;
}

// Six faces of four vertices each, so that every face has its own flat normal. Texture coordinates: each face
// fills one cell of a 3 x 2 grid over [0, 1]^2 (+x, -x, +y in the lower row; -y, +z, -z in the upper).
TriangleMesh make_box(glm::vec3 size) {
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 x(h.x, 0.0f, 0.0f), y(0.0f, h.y, 0.0f), z(0.0f, 0.0f, h.z);
  const glm::vec3 ex(1.0f, 0.0f, 0.0f), ey(0.0f, 1.0f, 0.0f), ez(0.0f, 0.0f, 1.0f);
  TriangleMesh mesh;
  int face = 0;
  auto add_box_face = [&](glm::vec3 center, glm::vec3 u, glm::vec3 v, glm::vec3 n) {
    const glm::vec2 cell(1.0f / 3.0f, 0.5f), lower = cell * glm::vec2(face % 3, face / 3);
    add_face(mesh, center, u, v, n, lower, face % 3 == 2 ? glm::vec2(1.0f, lower.y + cell.y) : lower + cell);
    ++face;
  };
  add_box_face(x, y, z, ex);
  add_box_face(-x, z, y, -ex);
  add_box_face(y, z, x, ey);
  add_box_face(-y, x, z, -ey);
  add_box_face(z, x, y, ez);
  add_box_face(-z, y, x, -ez);
  return mesh;
}

// Revolves a closed profile polygon in the (r, y) half-plane about the y axis. Profile points on the axis
// (r = 0) become single pole vertices and edges along the axis produce nothing, so a closed profile gives a
// watertight mesh. Normals are smooth across profile corners flatter than crease_deg and split at sharper ones.
// Texture coordinates: u = phi / 2 pi (the seam at phi = 0 duplicated), v = arc length along the profile (in its
// clockwise order in the (r, y) plane) over the length of the edges that make surface; every edge is its own band
// of rings, and a pole has one vertex per segment, at the middle of the segment's u range.
TriangleMesh make_lathe(std::span<const glm::vec2> profile_in, int segments, float crease_deg) {
  segments = std::max(segments, 3);
  std::vector<glm::vec2> profile(profile_in.begin(), profile_in.end());
  const auto n = static_cast<int>(profile.size());
  // Traverse clockwise in the (r, y) plane (r right, y up): the outward normal of edge a -> b is (-dy, dr).
  double twice_area = 0.0;
  for (int i = 0; i < n; ++i) {
    glm::vec2 a = profile[i], b = profile[(i + 1) % n];
    twice_area += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
  }
  if (twice_area > 0.0) std::reverse(profile.begin(), profile.end());
  auto edge_normal = [&](int i) {
    glm::vec2 d = profile[(i + 1) % n] - profile[i];
    return glm::normalize(glm::vec2(-d.y, d.x));
  };
  const float cos_crease = std::cos(glm::radians(crease_deg));
  auto makes_surface = [&](int i) { return profile[i].x > 0.0f || profile[(i + 1) % n].x > 0.0f; };
  float total_length = 0.0f, length_before = 0.0f;  // of the edges that make surface [scene units]
  for (int i = 0; i < n; ++i)
    if (makes_surface(i)) total_length += glm::length(profile[(i + 1) % n] - profile[i]);
  total_length = std::max(total_length, std::numeric_limits<float>::min());
  TriangleMesh mesh;
  for (int i = 0; i < n; ++i) {
    glm::vec2 a = profile[i], b = profile[(i + 1) % n];
    if (!makes_surface(i)) continue;  // along the axis: no surface
    const float v_a = std::min(length_before / total_length, 1.0f);
    length_before += glm::length(b - a);
    const float v_b = std::min(length_before / total_length, 1.0f);
    glm::vec2 e = edge_normal(i);
    glm::vec2 before = edge_normal((i + n - 1) % n), after = edge_normal((i + 1) % n);
    glm::vec2 na = glm::dot(e, before) >= cos_crease ? glm::normalize(e + before) : e;
    glm::vec2 nb = glm::dot(e, after) >= cos_crease ? glm::normalize(e + after) : e;
    // One ring of vertices per end of the edge: segments + 1 (the last a seam copy of the first), or where the
    // end lies on the axis, one pole vertex per segment.
    auto ring = [&](glm::vec2 p, glm::vec2 normal, float v) {
      const auto first = static_cast<std::uint32_t>(mesh.positions.size());
      const bool pole = p.x <= 0.0f;
      for (int s = 0; s < segments; ++s) {
        float phi = glm::two_pi<float>() * fraction(s, segments);
        glm::vec3 radial(std::cos(phi), 0.0f, -std::sin(phi));
        glm::vec3 n3 = pole ? glm::vec3(0.0f, normal.y >= 0.0f ? 1.0f : -1.0f, 0.0f)
                            : glm::normalize(glm::vec3(normal.x * radial.x, normal.y, normal.x * radial.z));
        glm::vec2 uv(pole ? fraction(2 * s + 1, 2 * segments) : fraction(s, segments), v);
        if (pole && s > 0) add_seam_copy(mesh, first, uv);
        else add_vertex(mesh, glm::vec3(std::max(p.x, 0.0f) * radial.x, p.y, std::max(p.x, 0.0f) * radial.z), n3, uv);
      }
      if (!pole) add_seam_copy(mesh, first, {1.0f, v});
      return std::pair{first, pole};
    };
    auto [ra, a_pole] = ring(a, na, v_a);
    auto [rb, b_pole] = ring(b, nb, v_b);
    // Vertex k (s or s + 1) of a ring, used by segment s: a pole's vertex of that segment.
    auto at = [&](std::uint32_t first, bool pole, int k, int s) { return first + u32(pole ? s : k); };
    // Outward face normal of this band, to orient each triangle counter-clockwise seen from outside.
    auto emit = [&](std::uint32_t i0, std::uint32_t i1, std::uint32_t i2) {
      glm::vec3 p0 = mesh.positions[i0], p1 = mesh.positions[i1], p2 = mesh.positions[i2];
      glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
      if (glm::dot(c, c) <= 0.0f) return;  // degenerate at a pole
      glm::vec3 outward = mesh.normals[i0] + mesh.normals[i1] + mesh.normals[i2];
      if (glm::dot(c, outward) >= 0.0f) add_triangle(mesh, i0, i1, i2);
      else add_triangle(mesh, i0, i2, i1);
    };
    for (int s = 0; s < segments; ++s) {
      emit(at(ra, a_pole, s, s), at(ra, a_pole, s + 1, s), at(rb, b_pole, s, s));
      emit(at(ra, a_pole, s + 1, s), at(rb, b_pole, s + 1, s), at(rb, b_pole, s, s));
    }
  }
  return mesh;
}

// A hollow sphere: the shell between inner_radius and radius (the inner surface faces the cavity).
TriangleMesh make_shell(float radius, float inner_radius, int segments) {
  std::vector<glm::vec2> profile;
  int arc = std::max(segments / 2, 2);
  for (int i = 0; i <= arc; ++i) {  // outer arc, top to bottom
    float theta = glm::pi<float>() * fraction(i, arc);
    profile.emplace_back(radius * std::sin(theta), radius * std::cos(theta));
  }
  for (int i = arc; i >= 0; --i) {  // inner arc, bottom to top
    float theta = glm::pi<float>() * fraction(i, arc);
    profile.emplace_back(inner_radius * std::sin(theta), inner_radius * std::cos(theta));
  }
  return make_lathe(profile, segments, 45.0f);
}

// size.x along x, size.y along z.
TriangleMesh make_plane(glm::vec2 size) {
  const glm::vec3 u(0.0f, 0.0f, 0.5f * size.y), v(0.5f * size.x, 0.0f, 0.0f);
  TriangleMesh mesh;
  add_face(mesh, glm::vec3(0.0f), u, v, {0.0f, 1.0f, 0.0f});
  return mesh;
}

}  // namespace lucent
