// test_bssrdf_models.cpp: the shared BSSRDF headers (the code the shaders compile) against the reference
// values of shared/spec/bssrdf-models.md and against closed forms.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "bssrdf/model.h"

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

}  // namespace
