// screen_space_kernel.cpp: the Burley-profile kernel of the screen-space method (screen_space_kernel.h).
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

double cdf(double u) {
  if (std::isinf(u)) return u > 0 ? 1.0 : 0.0;
  return 0.5 + std::copysign(marginal_half_cdf(std::fabs(u)), u);
}

}  // namespace

double marginal_half_cdf(double v) { return (integral_k0(v) + 3.0 * integral_k0(v / 3.0)) / (4.0 * M_PI); }

double marginal_half_moment(double v) {
  // integral over [0, v] of u K0(u) du = 1 - v K1(v)
  auto moment_k0 = [](double w) { return w <= 1e-12 ? 0.0 : w >= 700.0 ? 1.0 : 1.0 - w * std::cyl_bessel_k(1.0, w); };
  if (std::isinf(v)) return 10.0 / (4.0 * M_PI);
  return (moment_k0(v) + 9.0 * moment_k0(v / 3.0)) / (4.0 * M_PI);
}

glm::dvec3 burley_scale(const glm::vec3& sigma_a, const glm::vec3& sigma_s, const glm::vec3& g, float eta) {
  glm::dvec3 s;
  for (int b = 0; b < 3; ++b) {
    const double A = shader::diffuse_total_reflectance(sigma_a[b], sigma_s[b], g[b], eta);
    const double sigma_t_prime = sigma_a[b] + sigma_s[b] * (1.0 - g[b]);
    s[b] = (1.85 - A + 7.0 * std::pow(std::fabs(A - 0.8), 3.0)) * sigma_t_prime;
  }
  return s;
}

std::vector<shader::ScreenSpaceTapGPU> kernel_taps(const glm::vec3& sigma_a, const glm::vec3& sigma_s,
                                                   const glm::vec3& g, float eta, int taps) {
  const glm::dvec3 s = burley_scale(sigma_a, sigma_s, g, eta);
  // Interval boundaries at the j / N quantiles of the bands' mean marginal (equal shares of the mean kernel), by
  // bisection on its cumulative distribution; the outer ones at infinity.
  auto mean_cdf = [&](double x) { return (cdf(s.x * x) + cdf(s.y * x) + cdf(s.z * x)) / 3.0; };
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
    for (int c = 0; c < 3; ++c) m += (marginal_half_moment(s[c] * hi) - marginal_half_moment(s[c] * lo)) / s[c];
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
    for (int c = 0; c < 3; ++c) w[c] = static_cast<float>(cdf(s[c] * edge[k + 1]) - cdf(s[c] * edge[k]));
    out[k].tap = glm::vec4(w, static_cast<float>(x[k]));
  }
  return out;
}

std::vector<shader::ScreenSpaceTapGPU> scene_kernels(const Scene& scene, int taps) {
  std::vector<shader::ScreenSpaceTapGPU> out;
  for (const SceneObject& object : scene.objects) {
    if (!object.translucent()) continue;
    const Material& m = *object.material;
    std::vector<shader::ScreenSpaceTapGPU> k =
        kernel_taps(m.sigma_a * scene.scale_mm, m.sigma_s * scene.scale_mm, m.g, m.eta, taps);
    k.resize(LUCENT_SCREEN_SPACE_MAX_TAPS, shader::ScreenSpaceTapGPU{glm::vec4(0.0f)});
    out.insert(out.end(), k.begin(), k.end());
  }
  if (out.empty()) out.resize(LUCENT_SCREEN_SPACE_MAX_TAPS, shader::ScreenSpaceTapGPU{glm::vec4(0.0f)});
  return out;
}

}  // namespace lucent::methods::screen_space
