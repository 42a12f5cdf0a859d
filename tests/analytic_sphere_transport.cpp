// analytic_sphere_transport.cpp: see analytic_sphere_transport.h. Written apart from lucent's transport code on
// purpose (its own Fresnel, refraction, phase function and path tracer).
#include "analytic_sphere_transport.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lucent::test {
namespace {

double fresnel(double eta, double cos_i) {  // eta = n_transmitted / n_incident, cos_i >= 0
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Refraction of direction d at unit normal n facing d (d . n < 0) into relative index eta.
template <class V>
V refraction(const V& d, const V& n, double eta) {
  const double cos_i = -glm::dot(d, n);
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - (1.0 - cos_i * cos_i) / (eta * eta)));
  return glm::normalize(d / eta + (cos_i / eta - cos_t) * n);
}

double phase(double cos_theta, double g) {
  const double denominator = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (4.0 * M_PI * denominator * std::sqrt(denominator));
}

// Leg m of the light's ray with impact parameter b, in the plane's coordinates (along the light, across it).
struct Leg {
  glm::dvec2 start, direction;
  double length = 0.0;        // from start to the next boundary point
  double before = 0.0;        // path length inside before the leg starts
  double throughput = 0.0;    // T at entry times the internal reflectances so far
};

// The ray of impact parameter b from the light (plane coordinates: the light travels along +x; a point light sits
// at (-D, 0)): its direction, and where it meets the sphere.
struct Incoming {
  glm::dvec2 direction, entry;
};

Incoming incoming(const AnalyticSphere& s, double b) {
  const double R = s.radius;
  if (s.point_distance <= 0.0) return {glm::dvec2(1.0, 0.0), glm::dvec2(-std::sqrt(std::max(0.0, R * R - b * b)), b)};
  const double D = s.point_distance, sin_a = b / D;
  const glm::dvec2 o(-D, 0.0), d(std::sqrt(1.0 - sin_a * sin_a), sin_a);
  const double od = glm::dot(o, d), t = -od - std::sqrt(std::max(0.0, od * od - (D * D - R * R)));
  return {d, o + t * d};
}

Leg leg(const AnalyticSphere& s, double b, int m) {
  const double R = s.radius;
  Leg l;
  const Incoming in = incoming(s, b);
  glm::dvec2 p = in.entry, n = p / R;
  glm::dvec2 w = refraction(in.direction, n, s.eta);
  l.throughput = 1.0 - fresnel(s.eta, -glm::dot(in.direction, n));
  for (int j = 0; j < m; ++j) {
    const double t = -2.0 * glm::dot(p, w);
    p += t * w;
    l.before += t;
    n = p / R;
    l.throughput *= fresnel(1.0 / s.eta, std::abs(glm::dot(w, n)));
    w = glm::normalize(w - 2.0 * glm::dot(w, n) * n);
  }
  l.start = p;
  l.direction = w;
  l.length = -2.0 * glm::dot(p, w);
  return l;
}

double signed_distance(const AnalyticSphere& s, double b, int m, const glm::dvec2& X) {
  const Leg l = leg(s, b, m);
  const glm::dvec2 q = X - l.start;
  return q.x * l.direction.y - q.y * l.direction.x;
}

// The legs at the bracketing grid's impact parameters, per number of reflections (built once per sphere).
struct SphereLegTable {
  double radius = 0.0, eta = 0.0, point_distance = -1.0;
  int grid = 0, max_reflections = -1;
  std::vector<double> impact;
  std::vector<Leg> legs;
};

const SphereLegTable& leg_table(const AnalyticSphere& s) {
  thread_local SphereLegTable table;
  if (table.radius == s.radius && table.eta == s.eta && table.grid == s.grid &&
      table.max_reflections == s.max_reflections && table.point_distance == s.point_distance)
    return table;
  table.radius = s.radius, table.eta = s.eta, table.grid = s.grid, table.max_reflections = s.max_reflections;
  table.point_distance = s.point_distance;
  table.impact.resize(static_cast<std::size_t>(s.grid + 1));
  for (int i = 0; i <= s.grid; ++i)
    table.impact[static_cast<std::size_t>(i)] = s.radius * std::sin(M_PI * ((i + 0.5) / (s.grid + 1) - 0.5));
  table.legs.clear();
  for (int m = 0; m <= s.max_reflections; ++m)
    for (double b : table.impact) table.legs.push_back(leg(s, b, m));
  return table;
}

double exit_distance(const glm::dvec3& o, const glm::dvec3& d, double R) {  // from inside
  const double b = glm::dot(o, d), c = glm::dot(o, o) - R * R;
  return -b + std::sqrt(std::max(0.0, b * b - c));
}

glm::dvec3 sample_phase(reference::Rng& rng, const glm::dvec3& d, double g) {
  const double xi = rng.uniform();
  double cos_theta = 1.0 - 2.0 * xi;
  if (std::abs(g) > 1e-4) {
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    cos_theta = (1.0 + g * g - s * s) / (2.0 * g);
  }
  cos_theta = std::clamp(cos_theta, -1.0, 1.0);
  const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta), phi = 2.0 * M_PI * rng.uniform();
  const glm::dvec3 a = std::abs(d.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 u = glm::normalize(glm::cross(a, d)), v = glm::cross(d, u);
  return glm::normalize(sin_theta * (std::cos(phi) * u + std::sin(phi) * v) + cos_theta * d);
}

}  // namespace

double analytic_sphere_next_event(const AnalyticSphere& s, const glm::dvec3& x, const glm::dvec3& path_dir,
                                  double* by_reflections) {
  if (by_reflections)
    for (int m = 0; m <= s.max_reflections; ++m) by_reflections[m] = 0.0;
  const glm::dvec3 l = s.light_direction;
  const bool point = s.point_distance > 0.0;
  const double z = glm::dot(x, l);
  const glm::dvec3 across = x - z * l;
  const double rho = glm::length(across);
  if (!(rho > 1e-12 * s.radius)) return 0.0;  // on the axis: a set of measure zero
  const glm::dvec3 e_rho = across / rho;
  const glm::dvec2 X(z, rho);
  const double sigma_t = s.sigma_s + s.sigma_a;
  // A leg after m reflections starts at least m shortest chords (those of grazing rays) inside: chains whose light
  // is below 1e-12 of the irradiance on arrival are left out.
  const double shortest_chord = 2.0 * s.radius * std::sqrt(1.0 - 1.0 / (s.eta * s.eta));
  const SphereLegTable& table = leg_table(s);
  double L = 0.0;
  for (int m = 0; m <= s.max_reflections; ++m) {
    if (m > 0 && sigma_t * m * shortest_chord > 27.6) break;
    auto g_at = [&](int i) {
      const Leg& t = table.legs[static_cast<std::size_t>(m * (s.grid + 1) + i)];
      const glm::dvec2 q = X - t.start;
      return q.x * t.direction.y - q.y * t.direction.x;
    };
    double g_previous = g_at(0);
    for (int i = 1; i <= s.grid; ++i) {
      const double g = g_at(i), g_low0 = g_previous;
      g_previous = g;
      if ((g > 0.0) == (g_low0 > 0.0)) continue;
      double lo = table.impact[static_cast<std::size_t>(i - 1)], hi = table.impact[static_cast<std::size_t>(i)];
      double g_lo = g_low0;
      for (int k = 0; k < 52; ++k) {
        const double mid = 0.5 * (lo + hi), g_mid = signed_distance(s, mid, m, X);
        if ((g_mid > 0.0) == (g_lo > 0.0)) lo = mid, g_lo = g_mid; else hi = mid;
      }
      const double root = 0.5 * (lo + hi);
      const Leg leg_root = leg(s, root, m);
      const double along = glm::dot(X - leg_root.start, leg_root.direction);
      if (along < 0.0 || along > leg_root.length) continue;  // x is on the line but not on this leg
      const double h = 1e-7 * s.radius;
      const double slope = (signed_distance(s, root + h, m, X) - signed_distance(s, root - h, m, X)) / (2.0 * h);
      // A point light: its intensity over D^2 cos(alpha), alpha = asin(b / D) (the header's derivation).
      const double spread =
          point ? s.point_distance * s.point_distance * std::sqrt(1.0 - root * root / (s.point_distance * s.point_distance))
                : 1.0;
      const double fluence = s.irradiance * leg_root.throughput * std::abs(root) / (rho * std::abs(slope) * spread) *
                             std::exp(-sigma_t * (leg_root.before + along));
      const glm::dvec3 w = leg_root.direction.x * l + leg_root.direction.y * e_rho;  // the light's way at x
      const double part = fluence * phase(glm::dot(w, -path_dir), s.g);
      L += part;
      if (by_reflections) by_reflections[m] += part;
    }
  }
  return L;
}

double analytic_sphere_radiance(const AnalyticSphere& s, glm::dvec3 origin, glm::dvec3 direction, reference::Rng& rng) {
  const double R = s.radius;
  const double b = glm::dot(origin, direction), c = glm::dot(origin, origin) - R * R, discriminant = b * b - c;
  if (discriminant <= 0.0) return 0.0;
  const double t = -b - std::sqrt(discriminant);
  if (t <= 0.0) return 0.0;
  glm::dvec3 p = origin + t * direction, n = p / R;
  if (rng.uniform() < fresnel(s.eta, -glm::dot(direction, n))) return 0.0;  // reflected: nothing else to see
  glm::dvec3 d = refraction(direction, n, s.eta);
  double weight = 1.0 / (s.eta * s.eta), radiance = 0.0;
  const double sigma_t = s.sigma_s + s.sigma_a, albedo = s.sigma_s / sigma_t;
  for (int event = 0; event < 1000000; ++event) {
    const double boundary = exit_distance(p, d, R), flight = -std::log(1.0 - rng.uniform()) / sigma_t;
    if (flight < boundary) {
      p += flight * d;
      weight *= albedo;
      radiance += weight * analytic_sphere_next_event(s, p, d);
      d = sample_phase(rng, d, s.g);
    } else {
      p += boundary * d;
      n = p / R;
      if (rng.uniform() >= fresnel(1.0 / s.eta, std::abs(glm::dot(d, n)))) break;  // leaves: nothing outside
      d = glm::normalize(d - 2.0 * glm::dot(d, n) * n);
    }
    if (event >= 8) {  // Russian roulette below weight 1
      const double survive = std::min(1.0, weight);
      if (survive < 1.0) {
        if (rng.uniform() >= survive) break;
        weight /= survive;
      }
    }
  }
  return radiance;
}

}  // namespace lucent::test
