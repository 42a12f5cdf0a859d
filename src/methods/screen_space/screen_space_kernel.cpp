// screen_space_kernel.cpp: the profile kernel of the screen-space method (screen_space_kernel.h).
#include "methods/screen_space/screen_space_kernel.h"

#include <algorithm>
#include <cmath>

#include "bssrdf/diffuse_albedo.h"

namespace lucent::methods::screen_space {
namespace {

// G(v) = integral over [0, v] of K0(u) du, from a table of its values at t = sqrt(u) on [0, sqrt(60)] (the
// integrand in t, 2 t K0(t^2), is finite at 0), integrated once by the trapezoidal rule on 16384 steps (error
// below 1e-7) and interpolated linearly in t; G(inf) = pi / 2, reached to double precision by v = 60.
double integral_k0(double v) {
  constexpr int kSteps = 16384;
  static const std::vector<double> table = [] {
    const double h = std::sqrt(60.0) / kSteps;
    auto f = [](double t) { return t > 0.0 ? 2.0 * t * std::cyl_bessel_k(0.0, t * t) : 0.0; };
    std::vector<double> g(kSteps + 1, 0.0);
    for (int i = 1; i <= kSteps; ++i) g[static_cast<std::size_t>(i)] = g[static_cast<std::size_t>(i - 1)] + 0.5 * h * (f((i - 1) * h) + f(i * h));
    return g;
  }();
  if (v <= 0.0) return 0.0;
  if (v >= 60.0) return table.back();
  const double x = std::sqrt(v) / std::sqrt(60.0) * kSteps;
  const std::size_t i = std::min(static_cast<std::size_t>(x), static_cast<std::size_t>(kSteps - 1));
  const double f = x - static_cast<double>(i);
  return table[i] * (1.0 - f) + table[i + 1] * f;
}

double cdf(int profile, double u) {
  if (std::isinf(u)) return u > 0 ? 1.0 : 0.0;
  return 0.5 + std::copysign(marginal_half_cdf(profile, std::fabs(u)), u);
}

}  // namespace

double marginal_half_cdf(int profile, double v) {
  if (profile == LUCENT_SCREEN_SPACE_PROFILE_GAUSSIANS) {
    double h = 0.0;
    for (int i = 0; i < LUCENT_SCREEN_SPACE_GAUSSIANS; ++i)
      h += 0.5 * shader::kScreenSpaceGaussianWeight[i] * std::erf(v / std::sqrt(2.0 * shader::kScreenSpaceGaussianVariance[i]));
    return h;
  }
  return (integral_k0(v) + 3.0 * integral_k0(v / 3.0)) / (4.0 * M_PI);
}

double marginal_half_moment(int profile, double v) {
  if (profile == LUCENT_SCREEN_SPACE_PROFILE_GAUSSIANS) {
    // integral over [0, v] of u e^{-u^2 / (2 w)} / sqrt(2 pi w) du = sqrt(w / (2 pi)) (1 - e^{-v^2 / (2 w)})
    double m = 0.0;
    for (int i = 0; i < LUCENT_SCREEN_SPACE_GAUSSIANS; ++i) {
      const double w = shader::kScreenSpaceGaussianVariance[i];
      m += shader::kScreenSpaceGaussianWeight[i] * std::sqrt(w / (2.0 * M_PI)) *
           (std::isinf(v) ? 1.0 : 1.0 - std::exp(-v * v / (2.0 * w)));
    }
    return m;
  }
  // integral over [0, v] of u K0(u) du = 1 - v K1(v)
  auto moment_k0 = [](double w) { return w <= 1e-12 ? 0.0 : w >= 700.0 ? 1.0 : 1.0 - w * std::cyl_bessel_k(1.0, w); };
  if (std::isinf(v)) return 10.0 / (4.0 * M_PI);
  return (moment_k0(v) + 9.0 * moment_k0(v / 3.0)) / (4.0 * M_PI);
}

glm::dvec3 band_scales(const glm::vec3& sigma_a, const glm::vec3& sigma_s, const glm::vec3& g, float eta) {
  glm::dvec3 s;
  for (int b = 0; b < 3; ++b) s[b] = shader::burley_scale(sigma_a[b], sigma_s[b], g[b], eta);
  return s;
}

std::vector<shader::ScreenSpaceTapGPU> kernel_taps(const glm::vec3& sigma_a, const glm::vec3& sigma_s,
                                                   const glm::vec3& g, float eta, int taps, int profile) {
  const glm::dvec3 s = band_scales(sigma_a, sigma_s, g, eta);
  // Interval boundaries at the j / N quantiles of the bands' mean marginal (equal shares of the mean kernel), by
  // bisection on its cumulative distribution; the outer ones at infinity.
  auto mean_cdf = [&](double x) { return (cdf(profile, s.x * x) + cdf(profile, s.y * x) + cdf(profile, s.z * x)) / 3.0; };
  const double widest = 200.0 / std::max(1e-30, std::min({s.x, s.y, s.z}));
  std::vector<double> edge(static_cast<std::size_t>(taps) + 1);
  edge.front() = -INFINITY, edge.back() = INFINITY;
  for (int j = 1; j < taps; ++j) {
    const double q = static_cast<double>(j) / taps;
    double lo = -widest, hi = widest;
    for (int i = 0; i < 80; ++i) {
      const double mid = 0.5 * (lo + hi);
      (mean_cdf(mid) < q ? lo : hi) = mid;
    }
    edge[static_cast<std::size_t>(j)] = std::fabs(q - 0.5) < 1e-12 ? 0.0 : 0.5 * (lo + hi);
  }
  // Each tap at its interval's centroid under the mean marginal, so that the mean kernel's first moment (how far
  // light bleeds) is kept; 0 for an interval around the centre.
  auto moment = [&](double lo, double hi) {  // integral of |x| p_mean(x) over [lo, hi], 0 <= lo <= hi
    double m = 0.0;
    for (int c = 0; c < 3; ++c) m += (marginal_half_moment(profile, s[c] * hi) - marginal_half_moment(profile, s[c] * lo)) / s[c];
    return m / 3.0;
  };
  std::vector<double> x(static_cast<std::size_t>(taps));
  for (int j = 0; j < taps; ++j) {
    const double lo = edge[static_cast<std::size_t>(j)], hi = edge[static_cast<std::size_t>(j) + 1];
    const double mass = mean_cdf(hi) - mean_cdf(lo);
    if (lo >= 0.0)
      x[static_cast<std::size_t>(j)] = moment(lo, hi) / mass;
    else if (hi <= 0.0)
      x[static_cast<std::size_t>(j)] = -moment(-hi, -lo) / mass;
    else
      x[static_cast<std::size_t>(j)] = (moment(0.0, hi) - moment(0.0, -lo)) / mass;
  }
  std::vector<shader::ScreenSpaceTapGPU> out(static_cast<std::size_t>(taps));
  for (int j = 0; j < taps; ++j) {
    const std::size_t k = static_cast<std::size_t>(j);
    glm::vec3 w;
    for (int c = 0; c < 3; ++c) w[c] = static_cast<float>(cdf(profile, s[c] * edge[k + 1]) - cdf(profile, s[c] * edge[k]));
    out[k].tap = glm::vec4(w, static_cast<float>(x[k]));
  }
  return out;
}

std::vector<shader::ScreenSpaceTapGPU> scene_kernels(const Scene& scene, int taps, int profile) {
  std::vector<shader::ScreenSpaceTapGPU> out;
  for (const SceneObject& object : scene.objects) {
    if (!object.translucent()) continue;
    const Material& m = *object.material;
    std::vector<shader::ScreenSpaceTapGPU> k =
        kernel_taps(m.sigma_a * scene.scale_mm, m.sigma_s * scene.scale_mm, m.g, m.eta, taps, profile);
    k.resize(LUCENT_SCREEN_SPACE_MAX_TAPS, shader::ScreenSpaceTapGPU{glm::vec4(0.0f)});
    out.insert(out.end(), k.begin(), k.end());
  }
  if (out.empty()) out.resize(LUCENT_SCREEN_SPACE_MAX_TAPS, shader::ScreenSpaceTapGPU{glm::vec4(0.0f)});
  return out;
}

}  // namespace lucent::methods::screen_space
