// texture_gbuffer.h: the texture-space G-buffer: each translucent object's triangles drawn at their atlas texture
// coordinates (SceneGpu's world-space vertices, so deforming objects follow their deformation every frame over
// their rest-pose coordinates). Per texel:
//   position  RGBA32F: xyz world position [scene units]; w: scene object index + 1 (0: empty texel)
//   normal    RGBA32F: xyz world unit normal (interpolated); w: A_S / A_T of the triangle, its world area per
//             atlas area [scene units^2 per texel] (Chang et al. 2008, Eqs. 6-7), positive where the texel's
//             centre lies on the triangle: the surface area the texel stands for, so the sum over texels of
//             f * max(w, 0) is the midpoint rule for the surface integral of f (Eq. 7). Negative (-A_S / A_T) on
//             texels the triangle only touches: they hold a surface point for lookups but no area.
// Rasterization is conservative: every texel whose square a triangle touches is written (llvmpipe has no
// conservative-raster extension): the geometry shader draws the triangle's texel-space bounding box grown by one
// texel, and the fragment shader keeps texels whose square overlaps the triangle (separating axes: the box and the
// three edges). A texel is written with the point of the triangle nearest its centre, and the nearest triangle
// wins (depth = distance), so texels a triangle covers at their centre hold exact interpolated values.
#pragma once
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "gpu/shader_program.h"
#include "shared/bindings.h"
#include "texture_space/scene_atlas.h"

namespace lucent::render {
class SceneGpu;
}

namespace lucent::texture_space {

// Binding points of the pass (passed to its shaders as #defines), in the texture-space ranges of
// shared/bindings.h: storage buffers
inline constexpr int kBindingVertices = 5;   // shader::VertexGPU per vertex: SceneGpu::vertex_buffer()
inline constexpr int kBindingIndices = 6;    // uint per triangle corner: SceneGpu::index_buffer()
inline constexpr int kBindingCornerUvs = 7;  // vec2 per triangle corner of index_buffer(): atlas coordinates
// and the texture units a method reading the G-buffer binds it to (bind_textures).
inline constexpr int kTexturePosition = 24;
inline constexpr int kTextureNormalRatio = 25;
static_assert(kBindingVertices >= LUCENT_TEXTURE_SPACE_STORAGE_FIRST && kBindingCornerUvs <= LUCENT_TEXTURE_SPACE_STORAGE_LAST);
static_assert(kTexturePosition >= LUCENT_TEXTURE_SPACE_TEX_FIRST && kTextureNormalRatio <= LUCENT_TEXTURE_SPACE_TEX_LAST);

class TextureGBuffer {
 public:
  // `scene_gpu` must have been built from with_atlas_meshes(scene, atlas), so that its translucent index ranges
  // are the atlas meshes' triangles in order. Throws lucent::Error when the textures cannot be allocated.
  TextureGBuffer(const render::SceneGpu& scene_gpu, const SceneAtlas& atlas);
  ~TextureGBuffer();
  TextureGBuffer(const TextureGBuffer&) = delete;
  TextureGBuffer& operator=(const TextureGBuffer&) = delete;

  // Draws every translucent mesh of the scene as it is in the vertex buffer now (after SceneGpu::update).
  void render(const render::SceneGpu& scene_gpu);
  void bind_textures(int position_unit = kTexturePosition, int normal_unit = kTextureNormalRatio) const;

  int size() const { return size_; }
  GLuint position() const { return position_; }
  GLuint normal_ratio() const { return normal_ratio_; }
  // The two textures read back (size^2 texels each, row 0 at v = 0), for tests and tools.
  std::vector<glm::vec4> read_position() const;
  std::vector<glm::vec4> read_normal_ratio() const;

 private:
  int size_;
  gpu::ShaderProgram program_;
  GLuint framebuffer_ = 0, position_ = 0, normal_ratio_ = 0, depth_ = 0, corner_uvs_ = 0, vao_ = 0;
};

}  // namespace lucent::texture_space
