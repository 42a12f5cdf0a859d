// material.cpp: BSSRDF model names, derived material coefficients, presets to materials, and the checks that
// turn bad material parameters into one-line lucent::Error messages naming the field and its allowed range.
#include "lucent/material.h"

#include <cmath>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent {

std::string_view to_string(BssrdfModel model) {
  switch (model) {
    case BssrdfModel::StandardDipole: return "standard";
    case BssrdfModel::DirectionalDipole: return "directional";
    case BssrdfModel::PhotonBeamDiffusion: return "photon-beam";
    case BssrdfModel::BetterDipole: return "better-dipole";
    case BssrdfModel::Tabulated: return "tabulated";
    case BssrdfModel::Multipole: return "multipole";
  }
  return "unknown";
}

std::optional<BssrdfModel> parse_bssrdf_model(std::string_view name) {
  if (name == "standard") return BssrdfModel::StandardDipole;
  if (name == "directional") return BssrdfModel::DirectionalDipole;
  if (name == "photon-beam") return BssrdfModel::PhotonBeamDiffusion;
  if (name == "better-dipole") return BssrdfModel::BetterDipole;
  if (name == "tabulated") return BssrdfModel::Tabulated;
  if (name == "multipole") return BssrdfModel::Multipole;
  return std::nullopt;
}

glm::vec3 Material::sigma_tr() const {
  const glm::vec3 sigma_t_prime = sigma_a + sigma_s_prime();
  return glm::sqrt(3.0f * sigma_a * sigma_t_prime);
}

Material material_from_preset(const MaterialPreset& preset) {
  Material material;
  material.name = preset.name;
  material.sigma_a = preset.sigma_a;
  material.sigma_s = preset.sigma_s;
  material.g = preset.g;
  material.eta = preset.eta;
  return material;
}

namespace {

constexpr const char* kCoefficientRange = "allowed range [0, inf) mm^-1";
constexpr const char* kPositiveRange = "allowed range (0, inf) mm^-1";
constexpr const char* kGRange = "allowed range (-1, 1)";
constexpr const char* kEtaRange = "allowed range [1, 3]";
constexpr const char* kDiffusionNeeds = "must be positive for the diffusion models";

[[noreturn]] void fail(const std::string& where, const std::string& problem, const char* range) {
  throw Error(fmt::format("{}: {}; {}", where, problem, range));
}

// An absorption or scattering coefficient: finite and non-negative.
void check_coefficient(const glm::vec3& value, const char* field, const std::string& where) {
  for (int i = 0; i < 3; ++i) {
    const float v = value[i];
    if (std::isnan(v)) fail(where, fmt::format("{}[{}] is NaN", field, i), kCoefficientRange);
    if (std::isinf(v)) fail(where, fmt::format("{}[{}] = {} is infinite", field, i, v), kCoefficientRange);
    if (v < 0.0f) fail(where, fmt::format("{}[{}] = {} is negative", field, i, v), kCoefficientRange);
  }
}

void check_g(const glm::vec3& g, const std::string& where) {
  for (int i = 0; i < 3; ++i) {
    if (std::isnan(g[i])) fail(where, fmt::format("g[{}] is NaN", i), kGRange);
    if (!(g[i] > -1.0f && g[i] < 1.0f)) fail(where, fmt::format("g[{}] = {} is out of range", i, g[i]), kGRange);
  }
}

void check_eta(float eta, const std::string& where) {
  if (std::isnan(eta)) fail(where, "eta is NaN", kEtaRange);
  if (!(eta >= 1.0f && eta <= 3.0f)) fail(where, fmt::format("eta = {} is out of range", eta), kEtaRange);
}

// The diffusion models divide by sigma_a and sigma_s' (through sigma_tr and the albedo): both must be > 0.
void check_diffusion_positive(const Material& material, const std::string& where) {
  const glm::vec3 sigma_s_prime = material.sigma_s_prime();
  for (int i = 0; i < 3; ++i) {
    if (!(material.sigma_a[i] > 0.0f)) {
      fail(where, fmt::format("sigma_a[{}] = {} {}", i, material.sigma_a[i], kDiffusionNeeds), kPositiveRange);
    }
    if (!(sigma_s_prime[i] > 0.0f)) {
      const std::string field = fmt::format("sigma_s'[{0}] = sigma_s[{0}] * (1 - g[{0}])", i);
      fail(where, fmt::format("{} = {} {}", field, sigma_s_prime[i], kDiffusionNeeds), kPositiveRange);
    }
  }
}

}  // namespace

void validate_medium(const Material& material, const std::string& where) {
  check_coefficient(material.sigma_a, "sigma_a", where);
  check_coefficient(material.sigma_s, "sigma_s", where);
  check_g(material.g, where);
  check_eta(material.eta, where);
  if (!(material.thickness_mm >= 0.0f && material.thickness_mm <= 1e30f))
    fail(where, fmt::format("thickness_mm = {} is out of range", material.thickness_mm), "allowed range [0, 1e30] mm");
  for (int i = 0; i < 3; ++i)
    if (!(material.sigma_a[i] + material.sigma_s[i] > 0.0f))
      fail(where, fmt::format("sigma_a[{0}] + sigma_s[{0}] = 0: the medium neither absorbs nor scatters in band {0}", i),
           kPositiveRange);
}

void validate_diffusion_medium(const Material& material, const std::string& where) {
  check_diffusion_positive(material, where);
}

void validate_material(const Material& material, const std::string& where) {
  validate_medium(material, where);
  check_diffusion_positive(material, where);
}

}  // namespace lucent
