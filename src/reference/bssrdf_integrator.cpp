// bssrdf_integrator.cpp: the model reference (see integrators.h).
//
// x_i is drawn by one-sample multiple importance sampling (balance heuristic) of two techniques:
//  - area: uniform over the object's surface (reaches every lit point, also far or behind x_o);
//  - probe: a point at distance rho from x_o in its tangent plane, rho ~ sigma_tr e^{-sigma_tr rho} for a band
//    chosen uniformly, projected onto the surface along n_o (one of the object's hits on that line, chosen
//    uniformly). It captures the near-field peak of the directional dipole (within ~D of x_o at normal
//    incidence) that area sampling alone almost never hits: on a marble slab area sampling alone returned
//    0.73 +- 0.07 of the true 1.12 after 4e5 samples.
// A fifth of the samples by area, four fifths by probes: on the marble bunny (80x60, 256 spp) this halved the
// variance x time against an even split (RMS standard error 0.044 -> 0.034 in 0.79 -> 0.66 s).
#include <algorithm>
#include <cmath>
#include <vector>

#include "bssrdf/model.h"
#include "reference/integrators.h"
#include "transport/random_walk.h"

namespace lucent::reference {
namespace {

// Share of x_i samples drawn by area; the rest by exponential probes around x_o.
constexpr double kAreaFraction = 0.2;

struct Probe {
  glm::dvec3 x_o, n_o, t1, t2;
  glm::dvec3 sigma_tr;
  double half_length;  // of the probe segment along n_o
};

// The number of hits of `object` on the segment of the line through `point` along n_o within half_length of the
// plane (at most 64). With `chosen`, one of them uniformly, by reservoir sampling (nothing is stored: this runs
// for every sample).
std::size_t probe_hits(const ReferenceScene& s, const Probe& p, int object, glm::dvec3 point, Rng* rng = nullptr,
                       SurfaceHit* chosen = nullptr) {
  std::size_t count = 0;
  double offset = glm::dot(point - p.x_o, p.n_o);
  glm::dvec3 start = point + (p.half_length - offset) * p.n_o;
  double travelled = 0.0;
  while (travelled < 2.0 * p.half_length && count < 64) {
    SurfaceHit hit = s.rt.intersect(start, -p.n_o, 2.0 * p.half_length - travelled);
    if (!hit.hit()) break;
    if (hit.object == object) {
      ++count;
      if (chosen && rng->uniform() * static_cast<double>(count) < 1.0) *chosen = hit;
    }
    travelled += hit.t;
    start = hit.position;
  }
  return count;
}

double probe_plane_pdf(const Probe& p, double rho) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) sum += p.sigma_tr[c] * std::exp(-p.sigma_tr[c] * rho);
  return sum / 3.0 / (2.0 * M_PI * std::max(rho, 1e-12));
}

// Area-measure density of the probe technique at x_i, given the number of the object's hits on the probe line
// through x_i (0 outside the probe segment).
double probe_pdf(const Probe& p, glm::dvec3 x_i, glm::dvec3 n_i, std::size_t hits_on_line) {
  glm::dvec3 d = x_i - p.x_o;
  double along = glm::dot(d, p.n_o);
  if (std::abs(along) > p.half_length || hits_on_line == 0) return 0.0;
  double rho = glm::length(d - along * p.n_o);
  return probe_plane_pdf(p, rho) * std::abs(glm::dot(n_i, p.n_o)) / static_cast<double>(hits_on_line);
}

// The same, for an x_i drawn by area sampling: the hits on its line are traced (only inside the segment).
double probe_pdf(const ReferenceScene& s, const Probe& p, int object, glm::dvec3 x_i, glm::dvec3 n_i) {
  if (std::abs(glm::dot(x_i - p.x_o, p.n_o)) > p.half_length) return 0.0;
  return probe_pdf(p, x_i, n_i, probe_hits(s, p, object, x_i));
}

// A probe sample; `hits_on_line` returns the number of hits it chose from (the pdf's divisor: the same line
// through the chosen x_i, so it is not traced again).
bool sample_probe(const ReferenceScene& s, const Probe& p, int object, Rng& rng, SurfaceHit& out,
                  std::size_t& hits_on_line) {
  int channel = std::min(2, static_cast<int>(rng.uniform() * 3.0));
  double rho = -std::log(1.0 - rng.uniform()) / p.sigma_tr[channel];
  double alpha = 2.0 * M_PI * rng.uniform();
  glm::dvec3 point = p.x_o + rho * (std::cos(alpha) * p.t1 + std::sin(alpha) * p.t2);
  hits_on_line = probe_hits(s, p, object, point, &rng, &out);
  return hits_on_line > 0;
}

// E * integral of S_d T12 cos over the lit surface for one x_i (the integrand, before dividing by the pdf).
// `offset_i`: x_i's self-intersection offset (SurfaceHit::offset).
glm::dvec3 integrand(const ReferenceScene& s, const ObjectData& o, const shader::BandMedium* media, glm::dvec3 x_i,
                     glm::dvec3 n_i, double offset_i, glm::dvec3 x_o, glm::dvec3 n_o) {
  glm::dvec3 sum(0.0);
  for (const DirectionalLight& light : s.scene.lights) {
    glm::dvec3 w_i = -glm::dvec3(light.direction);
    double cos_i = glm::dot(n_i, w_i);
    if (cos_i <= 0.0 || s.rt.occluded(x_i + offset_i * n_i, w_i)) continue;
    double T12 = shader::fresnel_transmittance(static_cast<float>(o.eta), static_cast<float>(cos_i));
    for (int c = 0; c < 3; ++c) {
      double S_d = shader::bssrdf_Sd(o.model, media[c], static_cast<float>(o.eta), glm::vec3(x_i), glm::vec3(w_i),
                                     glm::vec3(n_i), glm::vec3(x_o), glm::vec3(n_o));
      sum[c] += light.radiance[c] * S_d * T12 * cos_i;
    }
  }
  for (const PointLight& light : s.scene.point_lights) {
    glm::dvec3 w_i = glm::dvec3(light.position) - x_i;
    double d = glm::length(w_i);
    w_i /= d;
    double cos_i = glm::dot(n_i, w_i);
    if (cos_i <= 0.0 || s.rt.occluded(x_i + offset_i * n_i, w_i, d - offset_i - EmbreeScene::offset_at(glm::dvec3(light.position)))) continue;
    double T12 = shader::fresnel_transmittance(static_cast<float>(o.eta), static_cast<float>(cos_i));
    glm::dvec3 E = point_light_intensity(s, light, -w_i) * cos_i / (d * d);
    for (int c = 0; c < 3; ++c) {
      double S_d = shader::bssrdf_Sd(o.model, media[c], static_cast<float>(o.eta), glm::vec3(x_i), glm::vec3(w_i),
                                     glm::vec3(n_i), glm::vec3(x_o), glm::vec3(n_o));
      sum[c] += E[c] * S_d * T12;
    }
  }
  return sum;
}

// B(x_o) / pi, one MIS sample. A textured material's S_d takes the coefficients at x_o (uv_o), where the light
// leaves: the convention of the volpath reference (the medium of the point a camera path enters) and of engines'
// texture-driven subsurface scattering; the probes follow the same coefficients.
glm::dvec3 scattered_radiosity_over_pi(const ReferenceScene& s, int object, glm::dvec3 x_o, glm::dvec3 n_o,
                                       glm::dvec2 uv_o, Rng& rng) {
  const ObjectData& o = s.rt.object(object);
  const MediumCoefficients at_exit = o.medium_at(uv_o);
  shader::BandMedium media[3];
  Probe probe{x_o, n_o, {}, {}, {}, 0.0};
  const auto thickness = static_cast<float>(o.thickness_at(x_o));
  for (int c = 0; c < 3; ++c) {
    media[c] = shader::make_band_medium(static_cast<float>(at_exit.sigma_a[c]), static_cast<float>(at_exit.sigma_s[c]),
                                        static_cast<float>(o.g[c]));
    media[c].thickness = thickness;
    probe.sigma_tr[c] = media[c].sigma_tr;
  }
  orthonormal_basis(n_o, probe.t1, probe.t2);
  // Probes reach no farther than the object: a medium without absorption (sigma_tr 0, or rounded to 0 from an
  // albedo near 1) would otherwise spread them over an infinite plane and send rays from infinity. Any rate
  // keeps the estimate unbiased, as the area technique covers the whole surface.
  const double diameter = std::max(1e-30, glm::length(glm::dvec3(o.mesh_upper - o.mesh_lower)));
  probe.sigma_tr = glm::max(probe.sigma_tr, glm::dvec3(1e-3 / diameter));
  probe.half_length = std::min(diameter, 10.0 / std::min({probe.sigma_tr.x, probe.sigma_tr.y, probe.sigma_tr.z}));

  glm::dvec3 x_i, n_i;
  double offset_i = 0.0;
  const bool by_area = rng.uniform() < kAreaFraction;
  std::size_t hits_on_line = 0;
  if (by_area) {
    SurfaceSample a = s.rt.sample_surface(object, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform());
    x_i = a.position, n_i = a.normal, offset_i = a.offset;
  } else {
    SurfaceHit hit;
    if (!sample_probe(s, probe, object, rng, hit, hits_on_line)) return glm::dvec3(0.0);
    x_i = hit.position, n_i = hit.normal, offset_i = hit.offset;
  }
  glm::dvec3 f = integrand(s, o, media, x_i, n_i, offset_i, x_o, n_o);
  if (f == glm::dvec3(0.0)) return f;
  const double probe_density =
      by_area ? probe_pdf(s, probe, object, x_i, n_i) : probe_pdf(probe, x_i, n_i, hits_on_line);
  double pdf = kAreaFraction / o.area + (1.0 - kAreaFraction) * probe_density;
  return f / pdf;
}

// Irradiance at an opaque point from the light emerging from the translucent objects (what the real-time
// method carries with VPLs), one sample: a translucent object chosen uniformly, a point x_v uniform on its
// area, a shadow ray, and the emergent radiance T21 B(x_v) / pi estimated by one nested sample.
glm::dvec3 emergent_irradiance(const ReferenceScene& s, const SurfaceHit& hit, glm::dvec3 n, Rng& rng) {
  std::vector<int> translucent;
  for (int i = 0; i < s.rt.object_count(); ++i)  // (an empty surface, e.g. blobs at some instant, emits nothing)
    if (s.rt.object(i).translucent && s.rt.object(i).area > 0.0) translucent.push_back(i);
  if (translucent.empty()) return glm::dvec3(0.0);
  int object = translucent[std::min(translucent.size() - 1,
                                    static_cast<std::size_t>(rng.uniform() * static_cast<double>(translucent.size())))];
  const ObjectData& o = s.rt.object(object);
  SurfaceSample v = s.rt.sample_surface(object, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform());
  glm::dvec3 to_v = v.position - hit.position;
  double d = glm::length(to_v);
  glm::dvec3 w = to_v / d;
  double cos_x = glm::dot(n, w), cos_v = -glm::dot(v.normal, w);
  if (cos_x <= 0.0 || cos_v <= 0.0) return glm::dvec3(0.0);
  if (s.rt.occluded(hit.position + hit.offset * n, w, d - 2.0 * (hit.offset + v.offset))) return glm::dvec3(0.0);
  double T21 = shader::fresnel_transmittance(static_cast<float>(o.eta), static_cast<float>(cos_v));
  glm::dvec3 L_v = T21 * scattered_radiosity_over_pi(s, object, v.position, v.normal, v.uv, rng);
  double pdf = 1.0 / (o.area * static_cast<double>(translucent.size()));
  return L_v * cos_v * cos_x / (d * d) / pdf;
}

}  // namespace

glm::dvec3 bssrdf_radiance(const ReferenceScene& s, glm::dvec3 origin, glm::dvec3 direction, Rng& rng,
                           const SurfaceHit* first_hit, PathRecord* /*record: nothing to report*/) {
  const SurfaceHit hit = first_hit ? *first_hit : s.rt.intersect(origin, direction);
  if (!hit.hit()) return glm::dvec3(s.scene.render.background);
  const ObjectData& o = s.rt.object(hit.object);
  glm::dvec3 n = hit.normal;
  if (!o.translucent) {
    if (glm::dot(n, direction) > 0.0) n = -n;
    return direct_light_lambertian(s, hit, n) + o.albedo / M_PI * emergent_irradiance(s, hit, n, rng);
  }
  double cos_o = std::max(0.0, -glm::dot(n, direction));
  double T21 = shader::fresnel_transmittance(static_cast<float>(o.eta), static_cast<float>(cos_o));
  return T21 * scattered_radiosity_over_pi(s, hit.object, hit.position, n, hit.uv, rng);
}

}  // namespace lucent::reference
