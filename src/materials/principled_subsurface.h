// principled_subsurface.h: the medium behind Blender's Principled BSDF subsurface (Cycles random walk), as lucent
// coefficients: Blender 3.4's inputs (PrincipledSubsurface) and Blender 4's Principled v2 inputs
// (PrincipledV2Subsurface, which becomes the Blender 3.4 inputs of the same medium; see the end of this file).
//
// Source: Blender 3.4 Cycles, intern/cycles/kernel/svm/svm_closure.h (Principled node),
// kernel/closure/bssrdf.h (bssrdf_setup_radius) and kernel/integrator/subsurface_random_walk.h
// (subsurface_random_walk_remap), read from Debian's blender 3.4.1 package. Formulas in docs/materials.md:
//   colour   A = mix(base_color, subsurface_color, subsurface)      (surface albedo, per band)
//   radius   d = subsurface_radius * subsurface * scale_mm           [mm]
//   method random_walk (Blender's default): d *= sqrt(3 (1 - alpha')), alpha' solving Jensen's dipole total
//            R_d(alpha') = alpha'/2 (1 + exp(-4/3 A_F s)) exp(-s), s = sqrt(3 (1 - alpha')), A_F from the
//            Egan-Hilgeman F_dr fit at eta = subsurface_ior: d becomes the transport mean free path 1 / sigma_t'
//            for a diffusion length 1 / sigma_tr equal to the radius;
//   method random_walk_fixed_radius: d *= 1 / (4 pi);
//   g = clamp(subsurface_anisotropy, 0, 0.9); sigma_t = 1 / (d (1 - g)) [mm^-1];
//   single-scattering albedo alpha = the fit of Wrenninge, Villemin and Hery, "Path traced subsurface scattering
//            using anisotropic phase functions and non-exponential free flights" (Pixar TM 17-07, 2017), of the
//            index-matched half-space multiple-scattering albedo A as a function of alpha and g, inverted;
//   sigma_s = alpha sigma_t, sigma_a = (1 - alpha) sigma_t;
//   eta = 1: Cycles 3.4's walk has no refractive boundary (a path leaves where it first crosses the surface, and
//            subsurface_ior only sets the radius above); the Principled specular lobe is a separate BSDF that
//            lucent's renderers do not add. Measured against Cycles (docs/materials.md): with eta 1 lucent's
//            volpath renders a sphere 5-8% darker than Cycles; with eta = subsurface_ior 23-54% darker.
// Limits: Cycles raises alpha below 0.2 to 0.2 and darkens the walk by alpha / 0.2 (a tint lucent has no place for:
// lucent keeps the fitted alpha); the Christensen-Burley method has no medium and is refused (shader_material_json).
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "lucent/material.h"

namespace lucent {

enum class PrincipledMethod { RandomWalk, RandomWalkFixedRadius };

struct PrincipledSubsurface {
  glm::vec3 base_color{0.8f};                             // linear RGB [0, 1]
  float subsurface = 0.0f;                                // factor [0, 1]; scales the radius, mixes the colour
  glm::vec3 subsurface_radius{1.0f, 0.2f, 0.1f};          // [scene units]
  glm::vec3 subsurface_color{0.8f, 0.8f, 0.8f};           // linear RGB [0, 1]
  float subsurface_ior = 1.4f;                            // sets the radius (random_walk), clamped to [1.01, 3.8]
  float subsurface_anisotropy = 0.0f;                     // [0, 0.9] after Cycles' clamp
  PrincipledMethod method = PrincipledMethod::RandomWalk;
};

struct PrincipledConversion {
  Material material;               // sigma_a, sigma_s [mm^-1], g, eta 1
  glm::dvec3 albedo{0.0};          // A: the mixed colour Cycles inverts
  glm::dvec3 radius_mm{0.0};       // d after the method's scaling: 1 / sigma_t' [mm]
  glm::dvec3 alpha_prime{0.0};     // random_walk: Jensen's reduced albedo from A (else 0)
  glm::dvec3 alpha{0.0};           // single-scattering albedo sigma_s / sigma_t
};

// Jensen's dipole total diffuse reflectance of a reduced albedo, with A_F = (1 + F_dr) / (1 - F_dr) at eta, as
// Cycles writes it (4/3 A_F folded into one constant).
double cycles_dipole_rd(double alpha_prime, double eta);
// alpha' with cycles_dipole_rd(alpha', eta) = rd: 0 below rd 1e-4, 0.999999 at 0.995 and above (Cycles' ends).
double cycles_alpha_prime(double rd, double eta);
// The Wrenninge-Villemin-Hery single-scattering albedo for a half-space albedo A and g, clamped to [0, 0.999999].
double cycles_single_scattering_albedo(double albedo, double g);

// The medium; throws lucent::Error("<where>: <field> ...") for a NaN, a subsurface factor outside (0, 1], a radius
// <= 0, a colour outside [0, 1].
PrincipledConversion principled_subsurface_material(const PrincipledSubsurface& p, double scale_mm,
                                                    const std::string& where);

// Blender 4's Principled BSDF (v2). Read from Cycles 4.x: intern/cycles/scene/shader_nodes.cpp
// (PrincipledBsdfNode: sockets and compile), kernel/svm/closure.h (svm_node_closure_bsdf, the Principled case's
// subsurface part), kernel/closure/bssrdf.h (bssrdf_setup, bssrdf_setup_radius), and Blender's
// source/blender/nodes/shader/nodes/node_shader_bsdf_principled.cc (socket defaults and ranges):
//   closure weight base_color * subsurface_weight (a diffuse closure takes 1 - subsurface_weight: a mix);
//   radius   = max(subsurface_radius * subsurface_scale, 0)   (the weight no longer scales it)
//   albedo   = base_color clamped to [0, 1]                   (no Subsurface Color socket)
//   ior      = the main IOR (after the Specular IOR Level adjustment), or Subsurface IOR under
//              random_walk_skin; bssrdf_setup clamps it to [1.01, 3.8] and g to [0, 0.9]
//   random_walk:      radius *= 1 / (4 pi)                    (Blender 3's random_walk_fixed_radius)
//   random_walk_skin: radius *= sqrt(3 (1 - alpha'(albedo, ior)))  (Blender 3's random_walk)
//   burley:           the Christensen-Burley disk profile, no medium.
// The walk itself (integrator/subsurface_random_walk.h) is Blender 3.4's: the same remap of albedo and radius to
// sigma_t and alpha, and a path leaves where it first crosses the surface; the IOR only bends the entry direction
// (integrator/subsurface.h, subsurface_entry_bounce) under random_walk, and sets the radius under
// random_walk_skin. So a v2 block is the v1 block subsurface 1, subsurface_color = base_color,
// subsurface_radius = radius * scale, with the method renamed.
enum class PrincipledV2Method { RandomWalk, RandomWalkSkin };

struct PrincipledV2Subsurface {
  glm::vec3 base_color{0.8f};                             // linear RGB [0, 1]: the subsurface albedo
  float subsurface_weight = 1.0f;                         // [0, 1]; lucent renders 1 only (no diffuse mix)
  glm::vec3 subsurface_radius{1.0f, 0.2f, 0.1f};          // per band, times subsurface_scale [scene units]
  float subsurface_scale = 0.05f;                         // [scene units]
  float ior = 1.5f;                                       // random_walk's entry only: no effect on the medium
  float subsurface_ior = 1.4f;                            // random_walk_skin: sets the radius
  float subsurface_anisotropy = 0.0f;                     // [0, 0.9] after Cycles' clamp
  PrincipledV2Method method = PrincipledV2Method::RandomWalk;
};

// The Blender 3.4 inputs of the same medium; throws lucent::Error("<where>: <field> ...") for a weight other than 1,
// a scale <= 0, a radius <= 0, a NaN.
PrincipledSubsurface principled_v1_equivalent(const PrincipledV2Subsurface& p, const std::string& where);
// principled_subsurface_material(principled_v1_equivalent(p)).
PrincipledConversion principled_v2_subsurface_material(const PrincipledV2Subsurface& p, double scale_mm,
                                                       const std::string& where);

}  // namespace lucent
