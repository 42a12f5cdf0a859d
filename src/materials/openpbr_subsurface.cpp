// openpbr_subsurface.cpp: see openpbr_subsurface.h.
#include "materials/openpbr_subsurface.h"

#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {

ArtistParameters openpbr_artist_parameters(const OpenPbrSubsurface& p, double scale_mm, BssrdfModel model,
                                           const std::string& where) {
  if (!(p.subsurface_weight == 1.0f))
    throw Error(fmt::format("{}: subsurface_weight = {}: lucent renders the subsurface slab alone (weight 1); a "
                            "weight of 0 is an opaque object (give it an albedo)", where, p.subsurface_weight));
  if (!(p.subsurface_radius > 0.0f && std::isfinite(p.subsurface_radius)))
    throw Error(fmt::format("{}: subsurface_radius = {} is out of range; allowed range (0, inf) scene units", where,
                            p.subsurface_radius));
  for (int band = 0; band < 3; ++band)
    if (!(p.subsurface_radius_scale[band] > 0.0f && std::isfinite(p.subsurface_radius_scale[band])))
      throw Error(fmt::format("{}: subsurface_radius_scale[{}] = {} is out of range; allowed range (0, inf)", where,
                              band, p.subsurface_radius_scale[band]));
  ArtistParameters a;
  a.albedo = p.subsurface_color;
  a.mfp_mm = glm::vec3(static_cast<double>(p.subsurface_radius) * glm::dvec3(p.subsurface_radius_scale) * scale_mm);
  a.g = glm::vec3(p.subsurface_scatter_anisotropy);
  a.eta = p.specular_ior;
  a.model = model;
  return a;
}

double van_de_hulst_single_scattering_albedo(double c, double g) {
  const double s = 4.09712 + 4.20863 * c - std::sqrt(9.59217 + 41.6808 * c + 17.7126 * c * c);
  return (1.0 - s * s) / (1.0 - g * s * s);
}

}  // namespace lucent
