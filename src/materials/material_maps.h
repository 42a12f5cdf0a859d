// material_maps.h: textured translucent materials: a surface-albedo texture and a mean-free-path texture read
// into lucent::MaterialMaps (lucent/material.h), inverted per texel to single-scattering albedos with the same
// flat-total curve as the uniform artist parameters (materials/artist_parameters.h).
//
// Files: PNG (8-bit; the albedo map is colour, sRGB-decoded as glTF's baseColorTexture; the mfp map is data, read
// as linear values in [0, 1]), OpenEXR and Radiance HDR (linear floats). Alpha is ignored; grey images have equal
// bands.
//
// Inversion: per distinct g (the bands usually share one), the model's flat total at normal incidence is
// tabulated at kAlbedoCurveNodes values of alpha, evenly spaced in log(1 - alpha) from kArtistAlphaMin to
// kArtistAlphaMax, and a texel's albedo is inverted by linear interpolation between the two nodes around it (the
// round trip is within 1e-4 of the exact total: tests/cpu/test_material_maps.cpp). Texel albedos outside the
// totals the model reaches are clamped to them, with one warning line that counts them.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/material.h"

namespace lucent {

inline constexpr int kAlbedoCurveNodes = 384;
// The largest map: 4096 x 4096 texels (192 MiB as RGB floats here, 256 MiB as the GPU's vec4 texels).
inline constexpr int kMaxMaterialMapSide = 4096;

// One band's flat total against alpha, for the inversion.
class AlbedoCurve {
 public:
  AlbedoCurve(BssrdfModel model, float g, float eta);  // model: the curve's (inversion_curve_model)
  double lowest() const { return totals_.front(); }    // total at kArtistAlphaMin
  double highest() const { return totals_.back(); }    // total at kArtistAlphaMax
  // alpha with total(alpha) = albedo, for albedo in [lowest(), highest()] (clamped to them).
  double alpha(double albedo) const;
  // The flat total at alpha, interpolated between the same nodes as alpha() (its exact inverse there; alpha
  // clamped to [kArtistAlphaMin, kArtistAlphaMax]): a map's albedo back from its alpha texels (the glTF export).
  double total(double alpha) const;
  // `albedo` clamped a thousandth of the reachable range inside [lowest(), min(highest(), 1)].
  double reachable(double albedo) const;
  double g() const { return g_; }

 private:
  float g_;
  std::vector<double> totals_;  // rising
};

// An image as the maps use it: RGB, rows from the bottom (v = 0) up.
struct MapImage {
  std::string file;
  glm::ivec2 size{0};
  std::vector<glm::vec3> texels;
};

// Reads a map file; `colour` decodes an 8-bit PNG's sRGB. Throws lucent::Error("<where>: <file>: <problem>") for
// an unreadable file, an unknown extension, or a value that is NaN, infinite or negative.
MapImage read_material_map(const std::string& file, bool colour, const std::string& where);

// The mean of a map's texels per band.
glm::vec3 map_mean(const MapImage& image);

// The material at its texels' extremes: the smallest alpha with the shortest mean free path (the shortest
// scattering length and the lowest albedo anywhere), for warnings that a mean would hide. The material itself when
// untextured.
Material densest_darkest(const Material& material);

// The maps of a material whose coefficients, g, eta and model are `base` (for an albedo map, `base` is the
// inversion of its mean albedo): alpha per texel from `albedo` (null: base's alpha everywhere), the mean free path
// per texel from `mfp_scale` times base's (null: base's everywhere). `where` names the material's JSON location;
// messages say "<where>/albedo_map: <file>: ...". Throws for an mfp texel <= 0 and for coefficients beyond a
// float; warns once per map about clamped albedos. Records base's g, eta and model in made_with_*; the caller
// records the material's final coefficients (made_with_sigma_*).
std::shared_ptr<MaterialMaps> make_material_maps(const Material& base, const MapImage* albedo,
                                                 const MapImage* mfp_scale, const std::string& where);

}  // namespace lucent
