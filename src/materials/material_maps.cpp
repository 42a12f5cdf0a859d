// material_maps.cpp: see material_maps.h.
#include "materials/material_maps.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "io/file_path_check.h"
#include "io/printable_text.h"
#include "lucent/warning.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/output_file.h"
#include "materials/artist_parameters.h"
#include "media/material_map.h"
#include "shared/tonemap.h"

namespace lucent {
namespace {

// The shaders' lookup (media/material_map.h).
glm::vec3 bilinear(const std::vector<glm::vec3>& texels, glm::ivec2 size, glm::vec2 uv) {
  const shader::MapTaps taps = shader::material_map_taps(uv, size);
  glm::vec3 sum(0.0f);
  for (int k = 0; k < 4; ++k) sum += taps.weight[k] * texels[static_cast<std::size_t>(taps.index[k])];
  return sum;
}

double alpha_of_node(int k) {
  const double lo = std::log1p(-kArtistAlphaMin), hi = std::log1p(-kArtistAlphaMax);
  const double u = lo + (hi - lo) * k / (kAlbedoCurveNodes - 1);
  return -std::expm1(u);
}


}  // namespace

glm::vec3 MaterialMaps::alpha_at(glm::vec2 uv) const {
  return alpha.empty() ? base_alpha : bilinear(alpha, alpha_size, uv);
}

glm::vec3 MaterialMaps::mfp_mm_at(glm::vec2 uv) const {
  return mfp_mm.empty() ? base_mfp_mm : bilinear(mfp_mm, mfp_size, uv);
}

void MaterialMaps::coefficients(glm::vec2 uv, glm::vec3& sigma_a, glm::vec3& sigma_s) const {
  const glm::vec3 a = alpha_at(uv), sigma_t = 1.0f / mfp_mm_at(uv);
  sigma_s = a * sigma_t;
  sigma_a = (1.0f - a) * sigma_t;
}

AlbedoCurve::AlbedoCurve(BssrdfModel model, float g, float eta) : g_(g) {
  totals_.resize(kAlbedoCurveNodes);
  for (int k = 0; k < kAlbedoCurveNodes; ++k) totals_[k] = flat_total_of_albedo(model, alpha_of_node(k), g, eta);
  for (int k = 1; k < kAlbedoCurveNodes; ++k) totals_[k] = std::max(totals_[k], totals_[k - 1]);  // rising
}

double AlbedoCurve::reachable(double albedo) const {
  const double lo = lowest(), hi = std::min(1.0, highest()), margin = 1e-3 * (hi - lo);
  return std::clamp(albedo, lo + margin, hi - margin);
}

double AlbedoCurve::alpha(double albedo) const {
  if (!(albedo > totals_.front())) return alpha_of_node(0);
  if (!(albedo < totals_.back())) return alpha_of_node(kAlbedoCurveNodes - 1);
  const auto upper = std::upper_bound(totals_.begin(), totals_.end(), albedo);
  const int k = static_cast<int>(upper - totals_.begin()) - 1;  // totals_[k] <= albedo < totals_[k + 1]
  const double t = (albedo - totals_[k]) / std::max(totals_[k + 1] - totals_[k], 1e-300);
  // Linear in log(1 - alpha), the nodes' spacing.
  const double u0 = std::log1p(-alpha_of_node(k)), u1 = std::log1p(-alpha_of_node(k + 1));
  return -std::expm1(u0 + t * (u1 - u0));
}

double AlbedoCurve::total(double alpha) const {
  const double lo = std::log1p(-kArtistAlphaMin), hi = std::log1p(-kArtistAlphaMax);
  const double x = (std::log1p(-std::clamp(alpha, kArtistAlphaMin, kArtistAlphaMax)) - lo) / (hi - lo) *
                   (kAlbedoCurveNodes - 1);  // the node position, spaced evenly in log(1 - alpha)
  const int k = std::clamp(static_cast<int>(std::floor(x)), 0, kAlbedoCurveNodes - 2);
  const double t = std::clamp(x - k, 0.0, 1.0);
  return totals_[k] + t * (totals_[k + 1] - totals_[k]);
}

MapImage read_material_map(const std::string& file, bool colour, const std::string& where) {
  if (const std::string problem = file_path_problem(file); !problem.empty())
    throw Error(fmt::format("{}: {}: {}", where, printable_text(file), problem));
  MapImage out;
  out.file = file;
  const std::string ext = lowercase_extension(file);
  ImageRGBA32F image;
  try {
    if (ext == ".png") {
      // The size the header declares, before the pixels are decoded (a small file can declare gigabytes of them).
      if (const auto [width, height] = image_file_size(file); width > kMaxMaterialMapSide || height > kMaxMaterialMapSide)
        throw Error(fmt::format("{}: map is {}x{}; a material map may have at most {} texels on each side", file, width,
                                height, kMaxMaterialMapSide));
      const ImageRGBA8 png = read_png(file);
      image.width = png.width, image.height = png.height;
      image.pixels.resize(png.pixels.size());
      for (std::size_t i = 0; i < png.pixels.size(); ++i) {
        const float v = static_cast<float>(png.pixels[i]) / 255.0f;
        image.pixels[i] = colour && i % 4 != 3 ? shader::srgb_decode(v) : v;
      }
    } else if (ext == ".exr") {
      image = read_exr(file);
    } else if (ext == ".hdr") {
      image = read_hdr(file);
    } else {
      throw Error(fmt::format("{}: unknown image type '{}'; a map is .png, .exr or .hdr", file, ext));
    }
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", where, e.what()));
  }
  if (image.width > kMaxMaterialMapSide || image.height > kMaxMaterialMapSide)
    throw Error(fmt::format("{}: {}: map is {}x{}; a material map may have at most {} texels on each side", where,
                            file, image.width, image.height, kMaxMaterialMapSide));
  out.size = {image.width, image.height};
  out.texels.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.at(x, image.height - 1 - y);  // files store the top row first
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(p[c]) || p[c] < 0.0f)
          throw Error(fmt::format("{}: {}: texel ({}, {}) band {} = {}; map values are finite and >= 0", where, file,
                                  x, image.height - 1 - y, c, p[c]));
      }
      out.texels[static_cast<std::size_t>(y) * image.width + x] = glm::vec3(p[0], p[1], p[2]);
    }
  }
  return out;
}

glm::vec3 map_mean(const MapImage& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& t : image.texels) sum += glm::dvec3(t);
  return glm::vec3(sum / std::max<double>(1.0, static_cast<double>(image.texels.size())));
}

namespace {

// The advice for an albedo map with texels outside the model's range: the models that reach them all, or else the
// model that clamps the fewest texel values (0 and 1 are outside every model's range).
std::string albedo_map_advice(const MapImage& albedo, double texel_lo, double texel_hi, const Material& base,
                              std::size_t clamped) {
  if (!models_reaching(texel_lo, texel_hi, base.g, base.eta, base.model).empty())
    return models_reaching_advice(texel_lo, texel_hi, base.g, base.eta, base.model);
  const BssrdfModel own = inversion_curve_model(base.model);
  BssrdfModel fewest = own;
  std::size_t fewest_count = clamped;
  for (BssrdfModel model : {BssrdfModel::StandardDipole, BssrdfModel::DirectionalDipole,
                            BssrdfModel::PhotonBeamDiffusion, BssrdfModel::BetterDipole}) {
    if (model == own) continue;
    FlatTotalRange range[3];
    for (int c = 0; c < 3; ++c) range[c] = flat_total_range(model, base.g[c], base.eta);
    std::size_t count = 0;
    for (const glm::vec3& texel : albedo.texels)
      for (int c = 0; c < 3; ++c) count += range[c].contains(texel[c]) ? 0 : 1;
    if (count < fewest_count) fewest = model, fewest_count = count;
  }
  const std::string edges = "texel values of 0 (no light returns) and 1 (no absorption) are outside every model's range";
  if (fewest == own) return fmt::format("no other model clamps fewer; {}", edges);
  return fmt::format("the {} model clamps the fewest, {} (model \"{}\"); {}", to_string(fewest), fewest_count,
                     to_string(fewest), edges);
}

}  // namespace

std::shared_ptr<MaterialMaps> make_material_maps(const Material& base, const MapImage* albedo,
                                                 const MapImage* mfp_scale, const std::string& where) {
  auto maps = std::make_shared<MaterialMaps>();
  const glm::vec3 sigma_t = base.sigma_t();
  maps->base_alpha = base.sigma_s / sigma_t;
  maps->base_mfp_mm = 1.0f / sigma_t;
  maps->made_with_g = base.g;
  maps->made_with_eta = base.eta;
  maps->made_with_model = base.model;
  if (albedo) {
    maps->albedo_file = albedo->file;
    maps->alpha_size = albedo->size;
    const BssrdfModel curve_model = inversion_curve_model(base.model);
    std::vector<AlbedoCurve> curves;
    int band_curve[3];
    for (int c = 0; c < 3; ++c) {
      auto same = std::find_if(curves.begin(), curves.end(), [&](const AlbedoCurve& k) { return k.g() == base.g[c]; });
      if (same == curves.end()) curves.emplace_back(curve_model, base.g[c], base.eta), same = curves.end() - 1;
      band_curve[c] = static_cast<int>(same - curves.begin());
    }
    std::size_t clamped = 0;
    double texel_lo = 1.0, texel_hi = 0.0;  // the albedos the map asks for
    maps->alpha.resize(albedo->texels.size());
    for (std::size_t i = 0; i < albedo->texels.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const AlbedoCurve& curve = curves[static_cast<std::size_t>(band_curve[c])];
        const double a = albedo->texels[i][c];
        if (a > 1.0) {
          const int w = std::max(1, albedo->size.x);
          const int x = static_cast<int>(i % static_cast<std::size_t>(w)), y = static_cast<int>(i / static_cast<std::size_t>(w));
          throw Error(fmt::format("{}/albedo_map: {}: texel ({}, {}) band {} = {}; a surface albedo is at most 1 (a "
                                  "surface reflects at most the light that reaches it)",
                                  where, albedo->file, x, albedo->size.y - 1 - y, c, a));
        }
        // Clamped a thousandth of the range inside it, as the material's mean albedo is: alpha at the range's
        // ends is 1 - 1e-7, which float texels and their bilinear blend round to 1 (no absorption, an unbounded
        // diffusion length).
        if (a <= curve.lowest() || a >= curve.highest()) ++clamped;
        texel_lo = std::min(texel_lo, a), texel_hi = std::max(texel_hi, a);
        maps->alpha[i][c] = static_cast<float>(curve.alpha(curve.reachable(a)));
      }
    }
    if (clamped > 0) {
      const AlbedoCurve& curve = curves.front();
      warn(fmt::format(
          "{}/albedo_map: {}: {} of {} texel values are outside the surface albedos the {} model "
          "reaches ({:.4g}, {:.4g}) at g {} and eta {} (the map spans [{:.4g}, {:.4g}]); clamped to them; {}",
          where, albedo->file, clamped, 3 * albedo->texels.size(), to_string(curve_model), curve.lowest(),
          std::min(curve.highest(), 1.0), curve.g(), base.eta, texel_lo, texel_hi,
          albedo_map_advice(*albedo, texel_lo, texel_hi, base, clamped)));
    }
  }
  if (mfp_scale) {
    maps->mfp_file = mfp_scale->file;
    maps->mfp_size = mfp_scale->size;
    maps->mfp_mm.resize(mfp_scale->texels.size());
    for (std::size_t i = 0; i < mfp_scale->texels.size(); ++i) {
      const glm::vec3 mfp = maps->base_mfp_mm * mfp_scale->texels[i];
      for (int c = 0; c < 3; ++c) {
        // > 1e-30 mm and < 1e30 mm keep both coefficients finite, positive floats.
        if (!(mfp[c] > 1e-30f && mfp[c] < 1e30f)) {
          const int w = std::max(1, mfp_scale->size.x);
          const int x = static_cast<int>(i % static_cast<std::size_t>(w)), y = static_cast<int>(i / static_cast<std::size_t>(w));
          throw Error(fmt::format("{}/mfp_map: {}: texel ({}, {}) band {} scales the mean free path {} mm to {} mm; "
                                  "allowed range (1e-30, 1e+30) mm: a map value of 0 is no mean free path",
                                  where, mfp_scale->file, x, mfp_scale->size.y - 1 - y, c, maps->base_mfp_mm[c],
                                  mfp[c]));
        }
      }
      maps->mfp_mm[i] = mfp;
    }
  }
  maps->min_alpha = maps->alpha.empty() ? maps->base_alpha : glm::vec3(1.0f);
  for (const glm::vec3& a : maps->alpha) maps->min_alpha = glm::min(maps->min_alpha, a);
  maps->min_mfp_mm = maps->mfp_mm.empty() ? maps->base_mfp_mm : glm::vec3(3.0e38f);
  for (const glm::vec3& l : maps->mfp_mm) maps->min_mfp_mm = glm::min(maps->min_mfp_mm, l);
  return maps;
}

Material densest_darkest(const Material& material) {
  if (!material.maps) return material;
  Material m = material;
  m.sigma_s = material.maps->min_alpha / material.maps->min_mfp_mm;
  m.sigma_a = (1.0f - material.maps->min_alpha) / material.maps->min_mfp_mm;
  return m;
}

}  // namespace lucent
