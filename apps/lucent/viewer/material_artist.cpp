// material_artist.cpp: see material_artist.h.
#include "viewer/material_artist.h"

#include <exception>

namespace lucent::viewer {

std::optional<ArtistParameters> artist_parameters_of(const Material& m) {
  ArtistParameters artist;
  artist.g = m.g;
  artist.eta = m.eta;
  artist.model = m.model;
  const BssrdfModel curve = inversion_curve_model(m.model);
  for (int c = 0; c < 3; ++c) {
    const double sigma_a = m.sigma_a[c], sigma_s = m.sigma_s[c], sigma_t = sigma_a + sigma_s;
    if (!(sigma_t > 0.0) || !(sigma_a > 0.0)) return std::nullopt;
    artist.mfp_mm[c] = static_cast<float>(1.0 / sigma_t);
    artist.albedo[c] = static_cast<float>(flat_total_of_albedo(curve, sigma_s / sigma_t, m.g[c], m.eta));
  }
  return artist;
}

std::string apply_artist_parameters(Material& m, const ArtistParameters& edited) {
  ArtistParameters artist = edited;
  artist.g = m.g;
  artist.eta = m.eta;
  artist.model = m.model;
  try {
    const ArtistInversion inversion = invert_artist_parameters(artist, "material");
    m.sigma_a = inversion.material.sigma_a;
    m.sigma_s = inversion.material.sigma_s;
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace lucent::viewer
