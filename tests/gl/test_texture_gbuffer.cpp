// test_texture_gbuffer.cpp: the texture-space G-buffer (src/texture_space/texture_gbuffer.h) on llvmpipe: the texel
// at a random surface point's atlas coordinates is filled (conservative rasterization) with a position within that
// texel's footprint on the surface; the area ratios sum to the surface area; a deforming object's texels follow it.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "render/scene_gpu.h"
#include "shared/shader_io.h"
#include "texture_space/texture_gbuffer.h"

namespace {

using namespace lucent::texture_space;

struct SurfacePoint {
  glm::vec3 world;
  glm::vec2 uv;
  float footprint;  // world distance a texel's diagonal spans on this triangle [scene units]
};

// Largest singular value of the triangle's texture -> surface map [scene units per texel].
float sigma_max(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec2 ta, glm::vec2 tb, glm::vec2 tc) {
  glm::vec3 e1 = b - a, e2 = c - a;
  float length1 = glm::length(e1), cross = glm::length(glm::cross(e1, e2));
  glm::mat2 q(glm::vec2(length1, 0.0f), glm::vec2(glm::dot(e1, e2) / length1, cross / length1));
  glm::mat2 j = q * glm::inverse(glm::mat2(tb - ta, tc - ta));
  float f = j[0][0] * j[0][0] + j[0][1] * j[0][1] + j[1][0] * j[1][0] + j[1][1] * j[1][1], det = glm::determinant(j);
  return std::sqrt(0.5f * (f + std::sqrt(std::max(0.0f, f * f - 4.0f * det * det))));
}

// Uniform random points (area-weighted triangles) of a world-space mesh with atlas coordinates.
std::vector<SurfacePoint> random_points(const lucent::TriangleMesh& world, int size, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<double> cdf;
  double total = 0.0;
  for (std::size_t f = 0; f < world.indices.size(); f += 3) {
    glm::vec3 a = world.positions[world.indices[f]], b = world.positions[world.indices[f + 1]], c = world.positions[world.indices[f + 2]];
    total += 0.5 * glm::length(glm::cross(b - a, c - a));
    cdf.push_back(total);
  }
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<SurfacePoint> out;
  for (int i = 0; i < count; ++i) {
    std::size_t f = 3 * static_cast<std::size_t>(std::lower_bound(cdf.begin(), cdf.end(), u01(rng) * total) - cdf.begin());
    f = std::min(f, world.indices.size() - 3);
    float r1 = static_cast<float>(std::sqrt(u01(rng))), r2 = static_cast<float>(u01(rng));
    glm::vec3 l(1.0f - r1, r1 * (1.0f - r2), r1 * r2);
    std::uint32_t i0 = world.indices[f], i1 = world.indices[f + 1], i2 = world.indices[f + 2];
    SurfacePoint p;
    p.world = l.x * world.positions[i0] + l.y * world.positions[i1] + l.z * world.positions[i2];
    p.uv = l.x * world.uvs[i0] + l.y * world.uvs[i1] + l.z * world.uvs[i2];
    float s = static_cast<float>(size);
    p.footprint = std::sqrt(2.0f) * sigma_max(world.positions[i0], world.positions[i1], world.positions[i2], world.uvs[i0] * s,
                                              world.uvs[i1] * s, world.uvs[i2] * s);
    out.push_back(p);
  }
  return out;
}

struct Rendered {
  std::vector<glm::vec4> position, normal_ratio;
  std::vector<lucent::shader::VertexGPU> vertices;  // the scene's vertex buffer as drawn
};

// Checks every random point's texel, and that sum of max(w, 0) is the surface area; returns the largest error.
void expect_points_and_area(const lucent::Scene& prepared, const SceneAtlas& atlas, const Rendered& g, const char* what) {
  const int n = atlas.atlas.size;
  int empty = 0, wrong_object = 0, too_far = 0;
  double worst = 0.0, area = 0.0;
  for (std::size_t k = 0; k < atlas.object_index.size(); ++k) {
    const lucent::SceneObject& object = prepared.objects[atlas.object_index[k]];
    lucent::TriangleMesh world = lucent::transformed(object.mesh, object.world_from_object);
    world.uvs = object.mesh.uvs;
    area += lucent::surface_area(world);
    for (const SurfacePoint& p : random_points(world, n, 2000, 7 + static_cast<unsigned>(k))) {
      int x = std::clamp(static_cast<int>(p.uv.x * static_cast<float>(n)), 0, n - 1);
      int y = std::clamp(static_cast<int>(p.uv.y * static_cast<float>(n)), 0, n - 1);
      const glm::vec4& texel = g.position[static_cast<std::size_t>(y * n + x)];
      if (texel.w == 0.0f) {
        ++empty;
        continue;
      }
      wrong_object += texel.w != static_cast<float>(atlas.object_index[k] + 1);
      double distance = glm::length(glm::vec3(texel) - p.world);
      worst = std::max(worst, distance / p.footprint);
      too_far += distance > 1.001 * p.footprint + 1e-6;
    }
  }
  double texel_sum = 0.0;
  for (const glm::vec4& t : g.normal_ratio) texel_sum += std::max(0.0f, t.w);
  fmt::print("{}: empty {}, wrong object {}, beyond the footprint {}, worst distance {:.3f} footprints; area {:.6f} "
             "from texels vs {:.6f} ({:+.3f}%)\n",
             what, empty, wrong_object, too_far, worst, texel_sum, area, 100.0 * (texel_sum / area - 1.0));
  EXPECT_EQ(empty, 0) << what;
  EXPECT_EQ(wrong_object, 0) << what;
  EXPECT_EQ(too_far, 0) << what;
  EXPECT_NEAR(texel_sum / area, 1.0, 0.01) << what;
}

Rendered read_back(const lucent::render::SceneGpu& scene_gpu, const TextureGBuffer& gbuffer) {
  GLint bytes = 0;
  glGetNamedBufferParameteriv(scene_gpu.vertex_buffer(), GL_BUFFER_SIZE, &bytes);
  std::vector<lucent::shader::VertexGPU> vertices(static_cast<std::size_t>(bytes) / sizeof(lucent::shader::VertexGPU));
  glGetNamedBufferSubData(scene_gpu.vertex_buffer(), 0, bytes, vertices.data());
  return {gbuffer.read_position(), gbuffer.read_normal_ratio(), std::move(vertices)};
}

Rendered render_gbuffer(const lucent::Scene& prepared, const SceneAtlas& atlas) {
  lucent::render::SceneGpu scene_gpu(prepared);
  TextureGBuffer gbuffer(scene_gpu, atlas);
  gbuffer.render(scene_gpu);
  return read_back(scene_gpu, gbuffer);
}

lucent::Scene mesh_scene(lucent::TriangleMesh mesh, const std::string& name) {
  lucent::Scene scene;
  scene.source = name;
  lucent::SceneObject object;
  object.name = name;
  object.mesh = std::move(mesh);
  object.world_from_object = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.0f, -1.0f)), glm::vec3(2.0f));
  object.material = lucent::Material{};
  scene.objects.push_back(std::move(object));
  return scene;
}

TEST(TextureGBuffer, SphereTexelsHoldTheirSurfacePoints) {
  lucent::test::ensure_gl_context();
  lucent::TriangleMesh sphere = lucent::make_sphere(0.6f, 32, 64);
  sphere.uvs.clear();  // the atlas builder's charts, not the shape's own layout
  lucent::Scene scene = mesh_scene(sphere, "sphere");
  SceneAtlas atlas = build_scene_atlas(scene, {.size = 256});
  lucent::Scene prepared = with_atlas_meshes(scene, atlas);
  expect_points_and_area(prepared, atlas, render_gbuffer(prepared, atlas), "sphere, 256^2");
}

TEST(TextureGBuffer, BunnyTexelsHoldTheirSurfacePoints) {
  const char* bunny = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(bunny)) GTEST_SKIP() << bunny << " missing (Debian package glmark2-data)";
  lucent::test::ensure_gl_context();
  lucent::Scene scene = mesh_scene(lucent::load_mesh(bunny), "bunny");
  SceneAtlas atlas = build_scene_atlas(scene, {.size = 1024});
  lucent::Scene prepared = with_atlas_meshes(scene, atlas);
  expect_points_and_area(prepared, atlas, render_gbuffer(prepared, atlas), "bunny, 1024^2");
}

TEST(TextureGBuffer, TwoObjectsShareOneAtlas) {
  lucent::test::ensure_gl_context();
  lucent::Scene scene = lucent::default_scene();  // torus and sphere translucent, floor opaque
  SceneAtlas atlas = build_scene_atlas(scene, {.size = 512});
  lucent::Scene prepared = with_atlas_meshes(scene, atlas);
  expect_points_and_area(prepared, atlas, render_gbuffer(prepared, atlas), "default scene, 512^2");
}

// A bending object: after the scene's update to time t the re-rendered texels hold the deformed surface (the
// CPU's deformed_mesh of the same atlas mesh), and they moved from the rest pose. One SceneGpu and one G-buffer
// for both instants, as the renderer keeps them while the scene plays. (Creating a second SceneGpu and G-buffer
// right after destroying the first read back the first one's texels on NVIDIA 580.159 at their first render,
// although the vertex buffer held the deformed mesh; no GL error was raised. Not understood; the renderer does
// not destroy and recreate them between frames.)
TEST(TextureGBuffer, DeformingObjectTexelsFollowTheDeformation) {
  lucent::test::ensure_gl_context();
  lucent::Scene scene = lucent::parse_scene(R"({
    "objects": [ { "name": "column", "shape": "box", "size": [0.4, 2.0, 0.4], "material": "Marble",
                   "deform": { "type": "bend", "amplitude": 0.6, "period_s": 2.0 } } ]})", "bend.json", ".");
  SceneAtlas atlas = build_scene_atlas(scene, {.size = 256});
  lucent::Scene prepared = with_atlas_meshes(scene, atlas);
  const double t = 0.5;
  lucent::render::SceneGpu scene_gpu(prepared);
  TextureGBuffer gbuffer(scene_gpu, atlas);
  scene_gpu.update(0.0, nullptr);
  gbuffer.render(scene_gpu);
  const Rendered rest = read_back(scene_gpu, gbuffer);
  scene_gpu.update(t, nullptr);
  gbuffer.render(scene_gpu);
  const Rendered bent = read_back(scene_gpu, gbuffer);
  lucent::Scene frozen = lucent::scene_at_time(prepared, t);
  frozen.objects[0].mesh.uvs = prepared.objects[0].mesh.uvs;
  // The vertex buffer drawn holds the deformed positions (world space).
  const lucent::TriangleMesh world = lucent::transformed(frozen.objects[0].mesh, frozen.objects[0].world_from_object);
  ASSERT_GE(bent.vertices.size(), world.positions.size());
  float vertex_error = 0.0f;
  for (std::size_t v = 0; v < world.positions.size(); ++v)
    vertex_error = std::max(vertex_error, glm::length(glm::vec3(bent.vertices[v].position) - world.positions[v]));
  EXPECT_LT(vertex_error, 1e-4f) << "the vertex buffer does not hold the deformed mesh";
  expect_points_and_area(frozen, atlas, bent, "bending box at t = 0.5 s");
  int moved = 0;
  for (std::size_t i = 0; i < rest.position.size(); ++i)
    moved += rest.position[i].w > 0.0f && glm::length(glm::vec3(rest.position[i]) - glm::vec3(bent.position[i])) > 0.05f;
  EXPECT_GT(moved, 100);
}

}  // namespace
