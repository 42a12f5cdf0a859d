// openpbr_subsurface.h: OpenPBR Surface's subsurface slab as lucent artist parameters.
//
// Source: OpenPBR Surface specification (Academy Software Foundation), section "Subsurface": the interior medium
// has mean free path r = subsurface_radius * subsurface_radius_scale per band, extinction mu_t = 1 / r (unreduced);
// subsurface_color C is the multiple-scattering albedo of a semi-infinite slab per power transmitted through the
// dielectric interface (E_multi-scatter = (1 - E_spec) C, normal incidence, uniform light); the phase function is
// Henyey-Greenstein with g = subsurface_scatter_anisotropy; the interface is the specular dielectric, IOR
// specular_ior. The specification leaves the alpha(C) inversion to the implementation (van de Hulst's
// index-matched formula is its example).
//
// That C is lucent's surface albedo (materials/artist_parameters.h): the model's flat total per refracted power.
// So the conversion is albedo = C, mfp_mm = r * scale_mm, g, eta = specular_ior, inverted with the material
// model's own curve, which includes the interface the renderers apply. subsurface_weight mixes the subsurface slab
// with a diffuse slab in OpenPBR; lucent renders an object as one or the other: weights in (0, 1) are refused.
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "materials/artist_parameters.h"

namespace lucent {

struct OpenPbrSubsurface {
  float subsurface_weight = 1.0f;                      // (0, 1]: 1 is the only weight lucent renders
  glm::vec3 subsurface_color{0.8f};                    // C, linear RGB (0, 1)
  float subsurface_radius = 1.0f;                      // [scene units] > 0
  glm::vec3 subsurface_radius_scale{1.0f, 0.5f, 0.25f};
  float subsurface_scatter_anisotropy = 0.0f;          // g (-1, 1)
  float specular_ior = 1.5f;                           // OpenPBR's default
};

// The artist parameters of `p` for `model`; throws lucent::Error("<where>: <field> ...") for a weight other than 1,
// a radius or radius scale <= 0. The inversion (invert_artist_parameters) checks the rest.
ArtistParameters openpbr_artist_parameters(const OpenPbrSubsurface& p, double scale_mm, BssrdfModel model,
                                           const std::string& where);

// van de Hulst's index-matched single-scattering albedo for a multiple-scattering albedo C and g, the
// specification's example inversion: s = 4.09712 + 4.20863 C - sqrt(9.59217 + 41.6808 C + 17.7126 C^2),
// alpha = (1 - s^2) / (1 - g s^2). For comparison (docs/materials.md); lucent inverts with its model's curve.
double van_de_hulst_single_scattering_albedo(double c, double g);

}  // namespace lucent
