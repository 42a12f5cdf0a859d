// artist_parameters.cpp: see artist_parameters.h.
#include "materials/artist_parameters.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"
#include "materials/model_total_reflectance.h"

namespace lucent {
namespace {

constexpr double kTotalTolerance = 1e-7;  // |total(alpha) - A| at which the search stops
constexpr int kMaxSteps = 200;

[[noreturn]] void fail(const std::string& where, const std::string& problem, const std::string& range) {
  throw Error(fmt::format("{}: {}; allowed range {}", where, problem, range));
}

// Finite and inside (lo, hi) (open); `field[band]` named in the message.
void check_open_range(const glm::vec3& value, const char* field, double lo, double hi, const std::string& range,
                      const std::string& where) {
  for (int band = 0; band < 3; ++band) {
    const float v = value[band];
    if (std::isnan(v)) fail(where, fmt::format("{}[{}] is NaN", field, band), range);
    if (!(v > lo && v < hi)) fail(where, fmt::format("{}[{}] = {} is out of range", field, band, v), range);
  }
}

void check_inputs(const ArtistParameters& a, const std::string& where) {
  check_open_range(a.albedo, "albedo", 0.0, 1.0, "(0, 1)", where);
  check_open_range(a.mfp_mm, "mfp_mm", 0.0, HUGE_VAL, "(0, inf) mm", where);
  check_open_range(a.g, "g", -1.0, 1.0, "(-1, 1)", where);
  if (std::isnan(a.eta)) fail(where, "eta is NaN", "[1, 3]");
  if (!(a.eta >= 1.0f && a.eta <= 3.0f)) fail(where, fmt::format("eta = {} is out of range", a.eta), "[1, 3]");
}

// alpha with total(alpha) = target, by false position with the Illinois modification on [lo, hi], where
// total(lo) < target < total(hi) and total rises with alpha.
double solve_alpha(BssrdfModel model, float g, float eta, double target, double lo, double f_lo, double hi,
                   double f_hi) {
  f_lo -= target, f_hi -= target;
  int side = 0;  // which end moved last: halve the other end's residual when one end stays twice
  double alpha = 0.5 * (lo + hi);
  for (int step = 0; step < kMaxSteps && hi - lo > 1e-15; ++step) {
    alpha = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const double f = flat_total_of_albedo(model, alpha, g, eta) - target;
    if (std::abs(f) < kTotalTolerance) return alpha;
    if (f < 0.0) {
      lo = alpha, f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = alpha, f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return alpha;
}

std::string curve_name(BssrdfModel model) {
  const BssrdfModel curve = inversion_curve_model(model);
  if (curve == model) return fmt::format("the {} model", to_string(model));
  return fmt::format("the {} model (the {} model's inversion curve)", to_string(curve), to_string(model));
}

// The single-scattering albedo of one band; throws when the model's totals do not reach `albedo`, naming the
// models that do.
double band_alpha(const ArtistParameters& a, int band, const std::string& where) {
  const BssrdfModel curve = inversion_curve_model(a.model);
  const float g = a.g[band];
  const double lo = kArtistAlphaMin, hi = kArtistAlphaMax;
  const double total_lo = flat_total_of_albedo(curve, lo, g, a.eta);
  const double total_hi = flat_total_of_albedo(curve, hi, g, a.eta);
  const float target = a.albedo[band];
  const std::string range = fmt::format("({:.4g}, {:.4g}) for {} at g {} and eta {}", total_lo,
                                        std::min(total_hi, 1.0), curve_name(a.model), g, a.eta);
  const std::string advice = "; " + models_reaching_advice(target, target, a.g, a.eta, a.model);
  if (target <= total_lo)
    fail(where, fmt::format("albedo[{}] = {} is below the smallest flat total the model reaches", band, target),
         range + advice);
  if (target >= total_hi)
    fail(where, fmt::format("albedo[{}] = {} is above the largest flat total the model reaches", band, target),
         range + advice);
  return solve_alpha(curve, g, a.eta, target, lo, total_lo, hi, total_hi);
}

constexpr BssrdfModel kInvertibleModels[] = {BssrdfModel::StandardDipole, BssrdfModel::DirectionalDipole,
                                             BssrdfModel::PhotonBeamDiffusion, BssrdfModel::BetterDipole};

// "the standard model", "the standard and directional models", "the standard, directional and photon-beam models".
std::string model_list(const std::vector<BssrdfModel>& models) {
  std::string names;
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (i > 0) names += i + 1 == models.size() ? " and " : ", ";
    names += to_string(models[i]);
  }
  return fmt::format("the {} model{}", names, models.size() > 1 ? "s" : "");
}

}  // namespace

FlatTotalRange flat_total_range(BssrdfModel model, float g, float eta) {
  const BssrdfModel curve = inversion_curve_model(model);
  return {flat_total_of_albedo(curve, kArtistAlphaMin, g, eta),
          std::min(1.0, flat_total_of_albedo(curve, kArtistAlphaMax, g, eta))};
}

std::vector<BssrdfModel> models_reaching(double lo, double hi, const glm::vec3& g, float eta, BssrdfModel model) {
  std::vector<BssrdfModel> out;
  for (BssrdfModel candidate : kInvertibleModels) {
    if (candidate == inversion_curve_model(model)) continue;
    bool reaches = true;
    for (int band = 0; band < 3 && reaches; ++band) {
      if (band > 0 && g[band] == g[band - 1]) continue;
      const FlatTotalRange range = flat_total_range(candidate, g[band], eta);
      reaches = range.contains(lo) && range.contains(hi);
    }
    if (reaches) out.push_back(candidate);
  }
  return out;
}

std::string models_reaching_advice(double lo, double hi, const glm::vec3& g, float eta, BssrdfModel model) {
  const std::vector<BssrdfModel> models = models_reaching(lo, hi, g, eta, model);
  const std::string what = lo == hi ? "it" : "them all";
  if (!models.empty())
    return fmt::format("{} reach{} {} (model \"{}\")", model_list(models), models.size() > 1 ? "" : "es", what,
                       to_string(models.front()));
  FlatTotalRange widest{1.0, 0.0};
  for (BssrdfModel candidate : kInvertibleModels) {
    const FlatTotalRange range = flat_total_range(candidate, g.x, eta);
    widest.lowest = std::min(widest.lowest, range.lowest), widest.highest = std::max(widest.highest, range.highest);
  }
  return fmt::format("no lucent diffusion model reaches {} at g {} and eta {} (together they reach ({:.4g}, {:.4g}))",
                     what, g.x, eta, widest.lowest, widest.highest);
}

BssrdfModel inversion_curve_model(BssrdfModel model) {
  return model == BssrdfModel::Tabulated || model == BssrdfModel::Multipole ? BssrdfModel::StandardDipole : model;
}

double flat_total_of_albedo(BssrdfModel model, double alpha, float g, float eta) {
  Material m;
  m.sigma_s = glm::vec3(static_cast<float>(alpha));
  m.sigma_a = glm::vec3(static_cast<float>(1.0 - alpha));
  m.g = glm::vec3(g);
  m.eta = eta;
  m.model = model;
  return model_total_reflectance(m, 0.0).total.x;
}

ArtistInversion invert_artist_parameters(const ArtistParameters& artist, const std::string& where) {
  check_inputs(artist, where);
  ArtistInversion out;
  out.curve_model = inversion_curve_model(artist.model);
  for (int band = 0; band < 3; ++band) {
    const bool same_as_previous =
        band > 0 && artist.albedo[band] == artist.albedo[band - 1] && artist.g[band] == artist.g[band - 1];
    out.alpha[band] = same_as_previous ? out.alpha[band - 1] : band_alpha(artist, band, where);
  }
  Material& m = out.material;
  const glm::dvec3 sigma_t = 1.0 / glm::dvec3(artist.mfp_mm);
  m.sigma_s = glm::vec3(out.alpha * sigma_t);
  m.sigma_a = glm::vec3((1.0 - out.alpha) * sigma_t);
  m.g = artist.g;
  m.eta = artist.eta;
  m.model = artist.model;
  validate_material(m, where);  // an extreme mfp can still overflow or underflow a float coefficient
  Material curve = m;
  curve.model = out.curve_model;
  out.total = model_total_reflectance(curve, 0.0).total;
  return out;
}

}  // namespace lucent
