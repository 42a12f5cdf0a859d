// test_bssrdf_models.cpp: the shared BSSRDF headers (the code the shaders compile) against the reference
// values of shared/spec/bssrdf-models.md and against closed forms.
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "bssrdf/model.h"
#include "lucent/error.h"
#include "lucent/material.h"
#include "lucent/scene.h"

namespace {

using namespace lucent::shader;

// float32 tolerance: the spec's values come from the authors' double-precision code; the float32 evaluation
// (exp, sqrt and the 9th-order Fresnel-moment polynomial in single precision) agrees to ~6e-5 relative.
constexpr double kFloat32Relative = 2e-4;

const float kPotatoSigmaA[3] = {0.0024f, 0.009f, 0.12f};
const float kPotatoSigmaS[3] = {0.68f, 0.7f, 0.55f};

glm::vec3 potato_Sd(glm::vec3 w_i, glm::vec3 x_o, glm::vec3 n_o) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = directional_dipole_Sd(make_band_medium(kPotatoSigmaA[c], kPotatoSigmaS[c], 0.0f), 1.3f, glm::vec3(0.0f),
                                   w_i, glm::vec3(0, 0, 1), x_o, n_o);
  return out;
}

void expect_relative(glm::vec3 actual, glm::dvec3 expected, double tolerance) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance * expected[c]) << "band " << c;
}

struct PotatoCase {
  const char* name;
  glm::vec3 w_i, x_o, n_o;
  glm::dvec3 S_d;
};

const glm::vec3 kUp(0, 0, 1);
const glm::vec3 k45 = glm::normalize(glm::vec3(1, 0, 1));
const glm::vec3 k80(std::sin(glm::radians(80.0f)), 0.0f, std::cos(glm::radians(80.0f)));

const PotatoCase kPotatoCases[] = {
    {"normal r=0.1", kUp, {0.1f, 0, 0}, kUp, {8.019856e-02, 8.464636e-02, 7.343868e-02}},
    {"normal r=0.5", kUp, {0.5f, 0, 0}, kUp, {2.237964e-02, 2.280510e-02, 1.863656e-02}},
    {"normal r=1", kUp, {1, 0, 0}, kUp, {9.567225e-03, 9.536976e-03, 6.863451e-03}},
    {"normal r=2", kUp, {2, 0, 0}, kUp, {3.558839e-03, 3.410761e-03, 1.872209e-03}},
    {"normal r=4", kUp, {4, 0, 0}, kUp, {1.114858e-03, 9.862984e-04, 3.082317e-04}},
    {"normal r=8", kUp, {8, 0, 0}, kUp, {2.449902e-04, 1.806823e-04, 1.859256e-05}},
    {"45deg backward", k45, {1, 0, 0}, kUp, {7.457789e-03, 7.324598e-03, 5.256564e-03}},
    {"45deg forward", k45, {-1, 0, 0}, kUp, {1.309840e-02, 1.311380e-02, 9.990236e-03}},
    {"45deg side", k45, {0, 1, 0}, kUp, {9.682262e-03, 9.637006e-03, 7.066277e-03}},
    {"80deg forward", k80, {-2, 0, 0}, kUp, {5.225813e-03, 5.057729e-03, 3.188762e-03}},
    {"convex n_o", kUp, {1, 0, 0}, glm::normalize(glm::vec3(0.5f, 0, 1)), {1.137484e-02, 1.138617e-02, 8.419359e-03}},
    {"below plane", kUp, {1, 0, -0.2f}, glm::normalize(glm::vec3(0.2f, 0, 1)), {1.022235e-02, 1.020819e-02, 7.402744e-03}},
    {"back-lit", kUp, {1, 0, -2}, {0, 0, -1}, {6.608744e-03, 6.415903e-03, 4.759984e-03}},
};

TEST(DirectionalDipole, MatchesPotatoReferenceValues) {
  for (const PotatoCase& c : kPotatoCases) {
    SCOPED_TRACE(c.name);
    expect_relative(potato_Sd(c.w_i, c.x_o, c.n_o), c.S_d, kFloat32Relative);
  }
}

TEST(DirectionalDipole, DegenerateConfigurationIsFinite) {
  // x_o - x_i parallel to n_i: NaN in the authors' code; here finite and positive. The modified tangent plane
  // is undefined there, so the model is discontinuous: a point 1e-3 mm away tilts n_i* by 90 degrees. The
  // fallback n_i* = n_i lands within 6.8% (red, green) and 1.5% (blue) of the perturbed values (measured);
  // 10% allowed: a test that the fallback is a neighbour of the limit, not a continuity claim.
  glm::vec3 at = potato_Sd(kUp, {0, 0, -2}, {0, 0, -1});
  glm::vec3 near = potato_Sd(kUp, {1e-3f, 0, -2}, {0, 0, -1});
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(std::isfinite(at[c]));
    EXPECT_GT(at[c], 0.0f);
    EXPECT_NEAR(at[c], near[c], 0.10 * near[c]);
  }
  glm::vec3 same_point = potato_Sd(kUp, {0, 0, 0}, kUp);
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(same_point[c]));
}

TEST(DirectionalDipole, PotatoConstantsMatchSpec) {
  // Polynomial values quoted in the spec for eta = 1.3 (double precision). The 3 C2 polynomial cancels
  // terms of size ~1600 down to ~0.3, so float32 loses ~2.4e-5 absolute in C_E (measured); 5e-5 allowed.
  // Its effect on S_d stays within the 2e-4 of MatchesPotatoReferenceValues.
  EXPECT_NEAR(fresnel_c_phi(1.3f), 0.138676, 2e-6);
  EXPECT_NEAR(fresnel_c_e(1.3f), 0.351276, 5e-5);
  EXPECT_NEAR((1.0f - fresnel_c_e(1.3f)) / (2.0f * fresnel_c_phi(1.3f)), 2.338986, 2e-4);
  EXPECT_NEAR(1.0f / (4.0f * fresnel_c_phi(1.0f / 1.3f)), 1.065094, 2e-5);
  BandMedium m = make_band_medium(0.0024f, 0.68f, 0.0f);
  EXPECT_NEAR(m.D, 0.488472, 1e-6);
  EXPECT_NEAR(m.sigma_tr, 0.0700948, 1e-6);
}

TEST(Fresnel, TransmittanceMatchesSpecAndLimits) {
  EXPECT_NEAR(fresnel_transmittance(1.3f, 1.0f), 0.982987, 1e-6);  // ((1.3-1)/(1.3+1))^2 at normal incidence
  EXPECT_NEAR(fresnel_transmittance(1.3f, k45.z), 0.976183, 1e-6);
  EXPECT_NEAR(fresnel_transmittance(1.3f, k80.z), 0.663882, 1e-6);
  EXPECT_NEAR(fresnel_reflectance(1.0f, 0.3f), 0.0f, 1e-7);           // index-matched: no reflection
  EXPECT_FLOAT_EQ(fresnel_reflectance(1.3f, 0.0f), 1.0f);            // grazing incidence
  EXPECT_FLOAT_EQ(fresnel_reflectance(1.0f / 1.3f, 0.5f), 1.0f);     // total internal reflection (critical 0.64)
}

// Integrates the exact Fresnel reflectance moments and compares with the polynomial fits (spec table 1.4).
TEST(Fresnel, MomentPolynomialsMatchNumericalIntegration) {
  const double etas[] = {1.1, 1.2, 1.3, 1.4, 1.5};
  const double exact_2c1[] = {0.194345, 0.336306, 0.444457, 0.528985, 0.596346};
  for (int i = 0; i < 5; ++i) {
    double c1 = 0.0, c2 = 0.0;
    const int n = 200000;
    for (int k = 0; k < n; ++k) {
      double mu = (k + 0.5) / n;
      // Internal incidence: light inside the medium hits the boundary, relative index 1/eta.
      double F = fresnel_reflectance(static_cast<float>(1.0 / etas[i]), static_cast<float>(mu));
      c1 += F * mu / n, c2 += F * mu * mu / n;
    }
    EXPECT_NEAR(2.0 * c1, exact_2c1[i], 2e-5) << "eta " << etas[i];
    EXPECT_NEAR(2.0 * c1, fresnel_moment_2c1(static_cast<float>(etas[i])), 2e-3) << "polynomial fit, eta " << etas[i];
    (void)c2;
  }
}

// Closed-form total diffuse reflectance of the standard dipole, spec Section 2 and validation-values Section 4.
TEST(StandardDipole, ClosedFormTotalMatchesPublishedTable) {
  struct Row { float alpha, eta; double Rd; };
  const Row rows[] = {{0.5f, 1.0f, 0.08781}, {0.9f, 1.0f, 0.38558}, {0.99f, 1.0f, 0.74671}, {0.5f, 1.3f, 0.07451},
                      {0.9f, 1.3f, 0.29913}, {0.99f, 1.3f, 0.64453}, {0.5f, 1.5f, 0.07357}, {0.9f, 1.5f, 0.27466},
                      {0.99f, 1.5f, 0.58310}};
  for (const Row& r : rows) EXPECT_NEAR(standard_dipole_total_Rd(r.alpha, r.eta), r.Rd, 1e-5) << r.alpha << " " << r.eta;
}

double integrate_radial(const std::function<double(double)>& profile, double sigma_tr) {
  // 2 pi r f(r) over [0, inf): substitution r = -ln(1-u)/sigma_tr, midpoint rule in u, Kahan-free double sum.
  const int n = 400000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    double u = (k + 0.5) / n;
    double r = -std::log(1.0 - u) / sigma_tr;
    double dr_du = 1.0 / (sigma_tr * (1.0 - u));
    sum += 2.0 * M_PI * r * profile(r) * dr_du / n;
  }
  return sum;
}

TEST(StandardDipole, RadialIntegralReproducesClosedForm) {
  // Optical units (sigma_t' = 1): alpha' in {0.5, 0.9, 0.99}, eta in {1, 1.3}. Tolerance 2e-4 relative:
  // float32 evaluation of R_d accumulated in double over 4e5 points.
  for (float alpha : {0.5f, 0.9f, 0.99f})
    for (float eta : {1.0f, 1.3f}) {
      BandMedium m = make_band_medium(1.0f - alpha, alpha, 0.0f);
      double total = integrate_radial([&](double r) { return standard_dipole_Rd(m, eta, static_cast<float>(r)); },
                                      m.sigma_tr);
      double closed = standard_dipole_total_Rd(alpha, eta);
      EXPECT_NEAR(total, closed, 2e-4 * closed) << "alpha' " << alpha << " eta " << eta;
    }
}

TEST(StandardDipole, SkimmilkProfileMatchesSpec) {
  const float sigma_s_prime[3] = {0.70f, 1.22f, 1.90f}, sigma_a[3] = {0.0014f, 0.0025f, 0.0142f};
  struct Row { float r; double Rd[3]; };
  const Row rows[] = {{0.0f, {4.082255e-02, 1.239924e-01, 2.989017e-01}},
                      {0.5f, {3.457204e-02, 7.892213e-02, 1.186159e-01}},
                      {1.0f, {2.314369e-02, 3.496763e-02, 3.692696e-02}},
                      {2.0f, {9.190400e-03, 1.008452e-02, 9.071251e-03}},
                      {4.0f, {2.557426e-03, 2.547401e-03, 1.576181e-03}},
                      {8.0f, {6.178815e-04, 4.409368e-04, 1.263829e-04}}};
  for (const Row& row : rows)
    for (int c = 0; c < 3; ++c) {
      BandMedium m = make_band_medium(sigma_a[c], sigma_s_prime[c], 0.0f);
      EXPECT_NEAR(standard_dipole_Rd(m, 1.3f, row.r), row.Rd[c], kFloat32Relative * row.Rd[c]) << row.r << " " << c;
    }
}

TEST(DirectionalDipole, NormalIncidenceIsRotationallySymmetricAndObliqueFavoursForward) {
  // At normal incidence on a flat surface the profile depends on |x_o - x_i| only.
  for (float r : {0.3f, 1.0f, 3.0f}) {
    glm::vec3 a = potato_Sd(kUp, {r, 0, 0}, kUp), b = potato_Sd(kUp, {0, r, 0}, kUp);
    glm::vec3 c = potato_Sd(kUp, {-r * 0.6f, r * 0.8f, 0}, kUp);
    for (int band = 0; band < 3; ++band) {
      EXPECT_NEAR(a[band], b[band], 1e-5 * a[band]);
      EXPECT_NEAR(a[band], c[band], 1e-5 * a[band]);
    }
  }
  // Oblique incidence: more light emerges on the forward side (refracted direction) than on the backward side.
  for (float r : {0.5f, 1.0f, 2.0f}) {
    glm::vec3 forward = potato_Sd(k45, {-r, 0, 0}, kUp), backward = potato_Sd(k45, {r, 0, 0}, kUp);
    for (int band = 0; band < 3; ++band) EXPECT_GT(forward[band], backward[band]);
  }
}

// ---- photon beam diffusion (spec Section 3) ----------------------------------------------------------------

// Optical units of the spec's pbrt table: sigma_t = 1, albedo rho, g.
BandMedium optical_medium(float rho, float g) { return make_band_medium(1.0f - rho, rho, g); }

const float kPbdRho[4] = {0.5f, 0.9f, 0.99f, 0.999f};
const float kPbdRadius[8] = {0.01f, 0.05f, 0.1f, 0.5f, 1.0f, 2.0f, 4.0f, 8.0f};
constexpr float kPbdEta = 1.33f;
constexpr int kPbrtSamples = 100;

// 2 pi int_0^inf r f(r) dr: r = e^t, trapezoid in t over [1e-8, 400] (the single-scattering profile grows
// like r^-1.2 at 0, so the substitution keeps r f(r) dr = r^2 f dt smooth).
double integrate_radial_log(const std::function<double(float)>& profile) {
  const int n = 2000;
  const double t_0 = std::log(1e-8), t_1 = std::log(400.0), h = (t_1 - t_0) / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    double r = std::exp(t_0 + k * h);
    sum += (k == 0 || k == n ? 0.5 : 1.0) * 2.0 * M_PI * r * r * profile(static_cast<float>(r)) * h;
  }
  return sum;
}

TEST(PhotonBeamDiffusion, MatchesPbrtReferenceValues) {
  // pbrt-v3's BeamDiffusionMS / BeamDiffusionSS: 100 samples, no clamp (d_r_min = 0). Tolerance: the file's
  // float32 2e-4. The spec's numbers use pbrt's rounded Fresnel-moment coefficients (3 C2 cancels terms of
  // ~1600, so the rounding moves C2 by 4e-5 at eta = 1.33); measured: MS within 6.1e-5, SS within 6.8e-7.
  const double MS[4][8] = {
      {8.309298e-02, 4.308390e-02, 2.865161e-02, 6.231181e-03, 2.044231e-03, 3.807583e-04, 2.530447e-05, 2.210413e-07},
      {2.832664e-01, 1.531615e-01, 1.058396e-01, 2.945671e-02, 1.266700e-02, 3.857813e-03, 6.248529e-04, 2.974734e-05},
      {3.520805e-01, 1.944820e-01, 1.370337e-01, 4.328683e-02, 2.145325e-02, 8.497923e-03, 2.299928e-03, 3.404734e-04},
      {3.600973e-01, 1.996036e-01, 1.410898e-01, 4.551946e-02, 2.312296e-02, 9.618425e-03, 2.904068e-03, 5.707961e-04}};
  const double SS[4][8] = {
      {2.572465e+00, 3.857376e-01, 1.458082e-01, 5.950477e-03, 6.134005e-04, 1.882561e-05, 5.771102e-08, 1.977858e-12},
      {4.630436e+00, 6.943276e-01, 2.624547e-01, 1.071086e-02, 1.104121e-03, 3.388611e-05, 1.038798e-07, 3.560145e-12},
      {5.093480e+00, 7.637604e-01, 2.887001e-01, 1.178194e-02, 1.214533e-03, 3.727472e-05, 1.142678e-07, 3.916159e-12},
      {5.139784e+00, 7.707037e-01, 2.913247e-01, 1.188905e-02, 1.225574e-03, 3.761358e-05, 1.153066e-07, 3.951761e-12}};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 8; ++b) {
      SCOPED_TRACE(testing::Message() << "rho " << kPbdRho[a] << " r " << kPbdRadius[b]);
      BandMedium m = optical_medium(kPbdRho[a], 0.0f);
      EXPECT_NEAR(photon_beam_diffusion_Rms(m, kPbdEta, kPbdRadius[b], kPbrtSamples, 0.0f), MS[a][b],
                  kFloat32Relative * MS[a][b]);
      EXPECT_NEAR(photon_beam_single_scattering(m, kPbdEta, kPbdRadius[b], kPbrtSamples), SS[a][b],
                  kFloat32Relative * SS[a][b]);
    }
}

TEST(PhotonBeamDiffusion, EffectiveAlbedoMatchesSpecAndExactTransport) {
  // rho_eff = 2 pi int r (MS + SS) dr; the spec gives 5 digits (measured: within 1.2e-5; 5e-5 allowed, the MS
  // values being up to 6e-5 relative off, see above). Physics: the spec's exact transport (adding-doubling,
  // n = 1.33, per refracted photon) is exceeded by 3.6% to 9.8% (diffusion overestimates); a lost factor of 2
  // or pi, or a wrong albedo power, falls far outside 0-12%.
  const double rho_eff[4] = {0.06622, 0.29567, 0.67285, 0.89800};
  const double exact[4] = {0.06033, 0.28036, 0.64586, 0.86641};
  for (int a = 0; a < 4; ++a) {
    BandMedium m = optical_medium(kPbdRho[a], 0.0f);
    double total = integrate_radial_log([&](float r) {
      return photon_beam_diffusion_Rms(m, kPbdEta, r, kPbrtSamples, 0.0f) +
             photon_beam_single_scattering(m, kPbdEta, r, kPbrtSamples);
    });
    EXPECT_NEAR(total, rho_eff[a], 5e-5) << "rho " << kPbdRho[a];
    EXPECT_GT(total, exact[a]) << "rho " << kPbdRho[a];
    EXPECT_LT(total, 1.12 * exact[a]) << "rho " << kPbdRho[a];
  }
}

TEST(PhotonBeamDiffusion, SingleScatteringPhaseFunction) {
  // The spec's values have g = 0. Henyey-Greenstein integrates to 1 over the sphere; a forward-scattering
  // medium (g > 0) turns less of the downward beam back to the surface than an isotropic one, g < 0 more.
  for (float g : {-0.5f, 0.0f, 0.5f, 0.9f}) {
    double integral = 0.0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      float cos_theta = static_cast<float>(-1.0 + 2.0 * (k + 0.5) / n);
      integral += 2.0 * M_PI * henyey_greenstein(cos_theta, g) * 2.0 / n;
    }
    EXPECT_NEAR(integral, 1.0, 1e-3) << "g " << g;
  }
  auto single = [](float g) {
    return photon_beam_single_scattering(make_band_medium(0.1f, 0.9f, g), kPbdEta, 0.5f, kPbrtSamples);
  };
  EXPECT_LT(single(0.5f), single(0.0f));
  EXPECT_LT(single(0.0f), single(-0.5f));
}

TEST(PhotonBeamDiffusion, ClampOnlyRemovesEnergyNearTheSource) {
  // Total multiple-scattering exitance of the clamped profile S_d uses (32 samples) against pbrt's unclamped
  // one: the clamp lowers the profile within r < 0.25/(sigma_a + sigma_t) only, by 0.50% (rho 0.999) to 1.6%
  // (rho 0.5) of the total (measured); allowed: 0.2% to 2.5%. Bound: exitance <= 1.
  for (float rho : kPbdRho) {
    BandMedium m = optical_medium(rho, 0.0f);
    double clamped = integrate_radial_log([&](float r) {
      return photon_beam_diffusion_Rms(m, kPbdEta, r, kPhotonBeamSamples, photon_beam_d_r_min(m));
    });
    double unclamped =
        integrate_radial_log([&](float r) { return photon_beam_diffusion_Rms(m, kPbdEta, r, kPbrtSamples, 0.0f); });
    EXPECT_LT(unclamped, 1.0) << "rho " << rho;
    EXPECT_GT(1.0 - clamped / unclamped, 0.002) << "rho " << rho;
    EXPECT_LT(1.0 - clamped / unclamped, 0.025) << "rho " << rho;
  }
}

TEST(PhotonBeamDiffusion, ClampIsActiveWhereDrIsBelowTheMinimum) {
  // g = 0.9 separates the unreduced sigma_t of the clamp (Dal Corso et al. 2015) from sigma_t':
  // sigma_a = 0.1, sigma_s = 9, so d_r_min = 0.25 / 9.2 [length] (0.25 / 1.1 with sigma_t').
  BandMedium m = make_band_medium(0.1f, 9.0f, 0.9f);
  float d_r_min = photon_beam_d_r_min(m);
  EXPECT_NEAR(d_r_min, 0.25 / 9.2, 1e-7);
  // Independent double-precision evaluations of the same 32-point quadrature (eta = 1.33): with the clamp
  // 0.2261537 at r = 0 and 0.2255358 at r = 0.01; unclamped 0.3619857 at r = 0.
  EXPECT_NEAR(photon_beam_diffusion_Rms(m, kPbdEta, 0.0f, kPhotonBeamSamples, d_r_min), 0.2261537,
              kFloat32Relative * 0.2261537);
  EXPECT_NEAR(photon_beam_diffusion_Rms(m, kPbdEta, 0.01f, kPhotonBeamSamples, d_r_min), 0.2255358,
              kFloat32Relative * 0.2255358);
  EXPECT_NEAR(photon_beam_diffusion_Rms(m, kPbdEta, 0.0f, kPhotonBeamSamples, 0.0f), 0.3619857,
              kFloat32Relative * 0.3619857);
  // Beyond d_r_min every d_r >= r >= d_r_min: the clamp changes nothing.
  for (float r : {0.03f, 0.5f, 3.0f})
    EXPECT_EQ(photon_beam_diffusion_Rms(m, kPbdEta, r, kPhotonBeamSamples, d_r_min),
              photon_beam_diffusion_Rms(m, kPbdEta, r, kPhotonBeamSamples, 0.0f));
  // S_d (through the model switch) is the clamped profile, normalised by 1 / (pi (1 - 2 C1(1/eta))).
  float normalization = kInvPi / (4.0f * fresnel_c_phi(1.0f / kPbdEta));
  glm::vec3 up(0, 0, 1);
  float S_d = bssrdf_Sd(LUCENT_MODEL_PHOTON_BEAM_DIFFUSION, m, kPbdEta, glm::vec3(0.0f), up, up, glm::vec3(0.0f), up);
  EXPECT_NEAR(S_d, 0.2261537 * normalization, kFloat32Relative * 0.2261537 * normalization);
  // pbrt's scheme at the spec's r = 0.01, rho = 0.5: the clamp (0.25 / 1.5) lowers 8.31e-2 to 2.636829e-2.
  BandMedium half = optical_medium(0.5f, 0.0f);
  EXPECT_NEAR(photon_beam_diffusion_Rms(half, kPbdEta, 0.01f, kPbrtSamples, photon_beam_d_r_min(half)), 2.636829e-2,
              kFloat32Relative * 2.636829e-2);
}

TEST(PhotonBeamDiffusion, ProductionSampleCountMatchesHighCountIntegral) {
  // kPhotonBeamSamples points against 4096 (clamp on, sigma_t' = 1, eta = 1.3), 0 <= r <= 10/sigma_tr.
  // Measured against 2e4 points in double precision: within 0.65% for g = 0 at every r, within 0.63% for
  // g = 0.9 at r >= 0.05 (5.8% below, where its clamp is smaller); totals within 0.11%. Allowed: 1% and 0.2%.
  for (float g : {0.0f, 0.9f})
    for (float rho_prime : {0.3f, 0.5f, 0.8f, 0.9f, 0.99f, 0.999f}) {
      SCOPED_TRACE(testing::Message() << "g " << g << " rho' " << rho_prime);
      BandMedium m = make_band_medium(1.0f - rho_prime, rho_prime / (1.0f - g), g);
      float d_r_min = photon_beam_d_r_min(m);
      float sigma_tr = make_photon_beam_medium(m, 1.3f).sigma_tr;
      double total = 0.0, total_reference = 0.0;
      for (int k = 0; k <= 100; ++k) {
        float r = k == 0 ? 0.0f : 1e-3f * std::pow(1e4f / sigma_tr, static_cast<float>(k - 1) / 99.0f);
        float value = photon_beam_diffusion_Rms(m, 1.3f, r, kPhotonBeamSamples, d_r_min);
        float reference = photon_beam_diffusion_Rms(m, 1.3f, r, 4096, d_r_min);
        if (g == 0.0f || r >= 0.05f) {
          EXPECT_NEAR(value, reference, 0.01f * reference) << "r " << r;
        }
        double weight = static_cast<double>(r) * r;  // r dr on the geometric grid (common factors dropped)
        total += weight * value, total_reference += weight * reference;
      }
      EXPECT_NEAR(total, total_reference, 2e-3 * total_reference);
    }
}

TEST(PhotonBeamDiffusion, SdIsRadialAndSelectableByName) {
  // S_d depends on |x_o - x_i| only (pbrt's normal beam): incident direction and normals do not matter.
  BandMedium m = make_band_medium(kPotatoSigmaA[0], kPotatoSigmaS[0], 0.0f);
  float S_d = bssrdf_Sd(LUCENT_MODEL_PHOTON_BEAM_DIFFUSION, m, 1.3f, glm::vec3(0.0f), kUp, kUp, {1, 0, 0}, kUp);
  float other = bssrdf_Sd(LUCENT_MODEL_PHOTON_BEAM_DIFFUSION, m, 1.3f, glm::vec3(0.0f), k45, glm::vec3(1, 0, 0),
                          {0, 0.6f, -0.8f}, {0, 0, -1});
  EXPECT_FLOAT_EQ(S_d, other);
  EXPECT_NEAR(S_d, 5.532458e-03, kFloat32Relative * 5.532458e-03);  // potato red, r = 1 mm (double precision)
  // The enum value is the shader's model id, and "photon-beam" selects it in scene files.
  EXPECT_EQ(static_cast<int>(lucent::BssrdfModel::PhotonBeamDiffusion), LUCENT_MODEL_PHOTON_BEAM_DIFFUSION);
  EXPECT_EQ(lucent::to_string(lucent::BssrdfModel::PhotonBeamDiffusion), "photon-beam");
  EXPECT_EQ(lucent::parse_bssrdf_model("photon-beam"), lucent::BssrdfModel::PhotonBeamDiffusion);
  auto scene_with_model = [](const std::string& model) {
    return R"({"lights": [{"direction": [0, -1, 0]}], "objects": [{"shape": "sphere", "material": )"
           R"({"preset": "Potato", "model": ")" + model + R"("}}]})";
  };
  lucent::Scene scene = lucent::parse_scene(scene_with_model("photon-beam"), "test.json", "/nonexistent");
  ASSERT_TRUE(scene.objects[0].material.has_value());
  EXPECT_EQ(scene.objects[0].material->model, lucent::BssrdfModel::PhotonBeamDiffusion);
  try {
    lucent::parse_scene(scene_with_model("photon"), "test.json", "/nonexistent");
    ADD_FAILURE() << "unknown model accepted";
  } catch (const lucent::Error& error) {
    EXPECT_STREQ(error.what(),
                 "test.json: /objects/0/material/model: 'photon' is not one of {standard|directional|photon-beam|better-dipole|tabulated|multipole}");
  }
}

}  // namespace
