// procedural_shapes.cpp: sphere, torus, box and plane meshes centred at the origin, y up. Every triangle is
// counter-clockwise seen from outside: cross(p1 - p0, p2 - p0) points along the outward normal.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "lucent/mesh.h"

namespace lucent {
namespace {

void add_vertex(TriangleMesh& mesh, glm::vec3 p, glm::vec3 n) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(n);
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

// A flat rectangle spanning center +- u +- v with unit normal n, which must point along cross(u, v).
void add_face(TriangleMesh& mesh, glm::vec3 center, glm::vec3 u, glm::vec3 v, glm::vec3 n) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  add_vertex(mesh, center - u - v, n);
  add_vertex(mesh, center + u - v, n);
  add_vertex(mesh, center + u + v, n);
  add_vertex(mesh, center - u + v, n);
  add_triangle(mesh, base, base + 1, base + 2);
  add_triangle(mesh, base, base + 2, base + 3);
}

float fraction(int i, int n) { return static_cast<float>(i) / static_cast<float>(n); }

std::uint32_t u32(int i) { return static_cast<std::uint32_t>(i); }

}  // namespace

// rings: latitude bands from pole to pole (at least 2); segments: divisions around the y axis (at least 3).
// One vertex per pole; the poles are closed by triangle fans, so the mesh is watertight.
TriangleMesh make_sphere(float radius, int rings, int segments) {
  rings = std::max(rings, 2);
  segments = std::max(segments, 3);
  TriangleMesh mesh;
  add_vertex(mesh, {0.0f, radius, 0.0f}, {0.0f, 1.0f, 0.0f});
  for (int r = 1; r < rings; ++r) {
    float theta = glm::pi<float>() * fraction(r, rings);
    for (int s = 0; s < segments; ++s) {
      float phi = glm::two_pi<float>() * fraction(s, segments);
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      add_vertex(mesh, radius * n, n);
    }
  }
  add_vertex(mesh, {0.0f, -radius, 0.0f}, {0.0f, -1.0f, 0.0f});

  const std::uint32_t north = 0, south = u32(1 + (rings - 1) * segments);
  auto ring_vertex = [&](int r, int s) { return u32(1 + (r - 1) * segments + s % segments); };
  for (int s = 0; s < segments; ++s) {
    add_triangle(mesh, north, ring_vertex(1, s + 1), ring_vertex(1, s));
    for (int r = 1; r < rings - 1; ++r) {
      add_quad(mesh, ring_vertex(r, s), ring_vertex(r, s + 1),  //
               ring_vertex(r + 1, s), ring_vertex(r + 1, s + 1));
    }
    add_triangle(mesh, ring_vertex(rings - 1, s), ring_vertex(rings - 1, s + 1), south);
  }
  return mesh;
}

// The tube's centre circle has radius major_radius in the xz plane. rings: cross-sections around the y axis
// (at least 3); segments: divisions around each cross-section (at least 3).
TriangleMesh make_torus(float major_radius, float minor_radius, int rings, int segments) {
  rings = std::max(rings, 3);
  segments = std::max(segments, 3);
  TriangleMesh mesh;
  for (int r = 0; r < rings; ++r) {
    float u = glm::two_pi<float>() * fraction(r, rings);
    glm::vec3 radial(std::cos(u), 0.0f, std::sin(u));
    for (int s = 0; s < segments; ++s) {
      float v = glm::two_pi<float>() * fraction(s, segments);
      glm::vec3 n = std::cos(v) * radial + glm::vec3(0.0f, std::sin(v), 0.0f);
      add_vertex(mesh, major_radius * radial + minor_radius * n, n);
    }
  }
  auto vertex = [&](int r, int s) { return u32((r % rings) * segments + s % segments); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      add_quad(mesh, vertex(r, s), vertex(r, s + 1), vertex(r + 1, s), vertex(r + 1, s + 1));
  return mesh;
}

// Six faces of four vertices each, so that every face has its own flat normal.
TriangleMesh make_box(glm::vec3 size) {
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 x(h.x, 0.0f, 0.0f), y(0.0f, h.y, 0.0f), z(0.0f, 0.0f, h.z);
  const glm::vec3 ex(1.0f, 0.0f, 0.0f), ey(0.0f, 1.0f, 0.0f), ez(0.0f, 0.0f, 1.0f);
  TriangleMesh mesh;
  add_face(mesh, x, y, z, ex);
  add_face(mesh, -x, z, y, -ex);
  add_face(mesh, y, z, x, ey);
  add_face(mesh, -y, x, z, -ey);
  add_face(mesh, z, x, y, ez);
  add_face(mesh, -z, y, x, -ez);
  return mesh;
}

// Revolves a closed profile polygon in the (r, y) half-plane about the y axis. Profile points on the axis
// (r = 0) become single pole vertices and edges along the axis produce nothing, so a closed profile gives a
// watertight mesh. Normals are smooth across profile corners flatter than crease_deg and split at sharper ones.
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
  TriangleMesh mesh;
  for (int i = 0; i < n; ++i) {
    glm::vec2 a = profile[i], b = profile[(i + 1) % n];
    if (a.x <= 0.0f && b.x <= 0.0f) continue;  // along the axis: no surface
    glm::vec2 e = edge_normal(i);
    glm::vec2 before = edge_normal((i + n - 1) % n), after = edge_normal((i + 1) % n);
    glm::vec2 na = glm::dot(e, before) >= cos_crease ? glm::normalize(e + before) : e;
    glm::vec2 nb = glm::dot(e, after) >= cos_crease ? glm::normalize(e + after) : e;
    // One ring of vertices per end of the edge (a single pole vertex where the end lies on the axis).
    auto ring = [&](glm::vec2 p, glm::vec2 normal) {
      const auto first = static_cast<std::uint32_t>(mesh.positions.size());
      int count = p.x <= 0.0f ? 1 : segments;
      for (int s = 0; s < count; ++s) {
        float phi = glm::two_pi<float>() * fraction(s, segments);
        glm::vec3 radial(std::cos(phi), 0.0f, -std::sin(phi));
        glm::vec3 n3 = count == 1 ? glm::vec3(0.0f, normal.y >= 0.0f ? 1.0f : -1.0f, 0.0f)
                                  : glm::normalize(glm::vec3(normal.x * radial.x, normal.y, normal.x * radial.z));
        add_vertex(mesh, glm::vec3(std::max(p.x, 0.0f) * radial.x, p.y, std::max(p.x, 0.0f) * radial.z), n3);
      }
      return std::pair{first, count};
    };
    auto [ra, ca] = ring(a, na);
    auto [rb, cb] = ring(b, nb);
    auto at = [&](std::uint32_t first, int count, int s) { return first + (count == 1 ? 0u : u32(s % segments)); };
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
      emit(at(ra, ca, s), at(ra, ca, s + 1), at(rb, cb, s));
      emit(at(ra, ca, s + 1), at(rb, cb, s + 1), at(rb, cb, s));
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
