// local_global_precompute.h: the CPU preprocessing of the local-global method (Lensch, Goesele, Bekaert, Kautz,
// Magnor, Lang, Seidel, "Interactive Rendering of Translucent Objects", Pacific Graphics 2002, Section 5) and the
// layout of its bytes (what MethodSetup::precomputed holds). No GL; compiled into lucent_core.
//
// Over the scene atlas (rigid translucent objects, world space, coefficients in scene units):
//   texels    every atlas texel whose centre lies on a triangle: its surface point x_c, its area A (world area per
//             texel, A_S / A_T of texture_space/texture_gbuffer.h), its triangle and barycentric coordinates.
//   kernels   per texel q, scatter form: K_q(d) = response at texel q + d (7 x 7 offsets d, same object) to unit
//             irradiance on q, per band: A(q) R_d(|x_c(q) - x_c(q + d)|) (Section 5.3), the centre entry the
//             integral of R_d over a disk of area A(q) instead of A(q) R_d(0); minus the interpolated global and
//             direct responses when blending (Section 5.4).
//   vertices  one global basis function per welded vertex (vertices at equal world positions of one object, so
//             atlas seams and split corners share one hat); for every vertex the texels that feed it: the dual
//             weight dual_i(x_c) A (Eq. 10; dual_i = (3 / A_i) (4 lambda_i - 1), A_i the area of the triangles
//             around i) and the direct weights w_i per band (Section 5.4; 0 without blending).
//   global    F'_ij = (A_i / 3) R_d(|v_i - v_j|) per band for i != j (Section 5.2, diagonal zeroed, Section 5.4),
//             pairs farther apart than the object's cutoff radius dropped, stored by row j (CSR) so that
//             B_j = sum_i F'_ij E_i is a gather.
//   corners   the welded vertex of every corner of every translucent atlas mesh, in atlas object order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/material.h"
#include "lucent/params.h"
#include "lucent/scene.h"

namespace lucent::texture_space {
struct SceneAtlas;
}

namespace lucent::methods::local_global {

inline constexpr int kKernelRadius = 3;                      // 7 x 7 local kernels
inline constexpr int kKernelWidth = 2 * kKernelRadius + 1;
inline constexpr int kKernelTaps = kKernelWidth * kKernelWidth;
inline constexpr int kRingRadius = kKernelRadius + 1;        // the boundary of the 9 x 9 kernel (Section 5.4)

struct VertexTexel {
  std::uint32_t texel;  // compact texel index
  float dual;           // dual_i(x_c) A [scene units^0]: E_i^g += dual E(texel)
  glm::vec3 direct;     // w_i per band: B_i^d += w_i E(texel) [dimensionless]
};

struct FormFactor {
  std::uint32_t column;  // source vertex i
  glm::vec3 value;       // F'_ij per band
};

struct ObjectSummary {
  std::uint32_t scene_object = 0;   // index into Scene::objects
  std::uint32_t first_vertex = 0;   // its welded vertices
  std::uint32_t vertex_count = 0;
  std::uint32_t texel_count = 0;
  float cutoff_radius = 0.0f;       // pairs farther apart are not in F' [scene units]
  glm::vec3 total_reflectance{0.0f};  // integral of 2 pi r R_d over [0, the object's diameter] per band
};

struct LocalGlobalData {
  int atlas_size = 0;
  std::vector<ObjectSummary> objects;                 // atlas object order
  std::vector<std::uint32_t> texel_xy;                // per texel: x | y << 16
  std::vector<float> kernels;                         // per texel, per tap (dy + 3) * 7 + (dx + 3): r, g, b
  std::vector<std::uint32_t> vertex_offsets;          // vertex_count + 1 into vertex_texels
  std::vector<VertexTexel> vertex_texels;
  std::vector<std::uint32_t> row_offsets;             // vertex_count + 1 into form_factors
  std::vector<FormFactor> form_factors;
  std::vector<std::uint32_t> corner_vertex;           // per corner of each atlas mesh, in atlas object order
  std::size_t texel_count() const { return texel_xy.size(); }
  std::size_t vertex_count() const { return vertex_offsets.empty() ? 0 : vertex_offsets.size() - 1; }
};

// Method parameters the precomputation reads.
struct Settings {
  double cutoff = 1e-3;        // tail fraction of the total reflectance the dropped pairs may hold
  bool blend = true;           // Section 5.4: direct weights and corrected kernels
  double max_form_factors = 5e7;  // refuse (one line) a global matrix with more nonzero entries
  bool remesh = true;             // Section 5.1: translucent meshes remeshed to round triangles of one size
  double vertex_spacing_mm = 0.0; // their edge length [mm]; 0: vertex_spacing() of the object
  double max_vertices = 2e4;      // refuse (one line) a remeshed object with more vertices (estimated beforehand)
};
Settings settings_from(const ParamValues& params);

// Section 5.1 asks for "round triangles of similar size" without a size. The edge length used when
// vertex_spacing_mm is 0 [scene units]: the smaller of
//   - the shortest diffusion length 1 / sigma_tr over the bands: the hats interpolate R_d, which falls by e per
//     diffusion length, and a hat wider than that spreads the near field of F' over two edge lengths, beyond the
//     7 x 7 kernels' reach, so blending cannot remove the double count (the slab's box of 8 vertices);
//   - a fiftieth of the object's world bounding-box diagonal: the shape (ears, thin plates) survives when the
//     diffusion length is long.
double vertex_spacing(const Scene& scene, const SceneObject& object);

// The scene with every translucent object's mesh remeshed (Settings::remesh; remesh.h) in world space to the
// spacing, sharp edges kept; through the precompute cache (kind "local-global-remesh", keyed on the mesh, its
// transform, the spacing and the remesher's options). Throws lucent::Error "<scene>: object '<name>': ..." for a
// deforming object, and "<scene>: object '<name>': /method/vertex_spacing: ..." when the remeshed object would have
// more than max_vertices vertices.
Scene remeshed_scene(const Scene& scene, const Settings& settings, const std::function<void(double)>& progress);

// Throws lucent::Error "<scene>: object '<name>': ..." for a deforming or blob translucent object (rigid only).
void check_rigid(const Scene& scene);

// The precomputation; `scene` has the atlas meshes (with_atlas_meshes). progress(fraction) from 0 to 1.
LocalGlobalData compute(const Scene& scene, const texture_space::SceneAtlas& atlas, const Settings& settings,
                        const std::function<void(double)>& progress);

std::vector<std::byte> encode(const LocalGlobalData& data);
// Throws lucent::Error when the bytes are not an encoding of this version.
LocalGlobalData decode(std::span<const std::byte> bytes);

// The model's radial profile of one band and its integrals (numerical, on a geometric grid of radii).
class RadialProfile {
 public:
  // sigma_a, sigma_s [1/scene unit]; thickness: the multipole model's slab [scene units]; r_end: the largest radius
  // integrated [scene units].
  RadialProfile(int model, float sigma_a, float sigma_s, float g, float eta, float thickness, double r_end);
  double Rd(double r) const;                 // R_d(r) [1/scene unit^2]
  // R_d between two surface points with their normals (bssrdf_pair_Rd) [1/scene unit^2].
  double Rd(glm::dvec3 x_i, glm::dvec3 n_i, glm::dvec3 x_o, glm::dvec3 n_o) const;
  double disk_integral(double rho) const;    // integral of 2 pi r R_d(r) over [0, rho] (rho <= r_end)
  double total() const { return cumulative_.back(); }  // over [0, r_end]
  double tail_radius(double fraction) const; // smallest r with total - disk_integral(r) <= fraction total
 private:
  int model_;
  float eta_;
  float sigma_a_, sigma_s_, g_, thickness_;
  std::vector<double> radius_, cumulative_;
};

}  // namespace lucent::methods::local_global
