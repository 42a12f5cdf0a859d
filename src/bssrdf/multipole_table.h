// multipole_table.h: the "multipole" BSSRDF model: the reflectance and transmittance profiles of a slab of finite
// thickness (multipole.h, with the light spread along the refracted beam), read from a table per band medium.
//
// Why a table: one evaluation of the beam profiles sums 2 (2 kMultipolePairs + 1) exponentials per depth of the beam
// (about 4,000 per sample at 64 depths); the table makes a sample cost a few reads, like the standard dipole.
// What it holds, per reduced albedo alpha' and eta (lengths in reduced mean free paths, r' = r sigma_t', so one
// table serves every scale of the medium): for kMultipoleTableD optical thicknesses d' (log-spaced, a factor 2^(1/3)
// apart, from kMultipoleTableDMin to kMultipoleTableDMax), the bin averages of R'(r') and T'(r') over the radial bins
// of the tabulated model (bssrdf/tabulated.h: [0, r'_min], then log-spaced up to r'_max), each row rescaled so that
// its interpolation carries the row's power. The bin averages come from each source's closed-form plane integral
// over an annulus (2 pi z [e^(-s d(a)) / d(a) - e^(-s d(b)) / d(b)], d(r) = sqrt(r^2 + z^2)), so the rows sum to
// multipole_beam_totals; nothing is fitted.
// Layout (kMultipoleTableFloats floats; it lives in the tabulated model's table buffer, whose directory names it by
// albedo alpha', g kMultipoleTableKey and eta): [0] r'_max, [1] 1 / q and [2] c_1 of bssrdf_table_r_coord (q the log
// of the bins' edge ratio, c_1 the centre of bin 1), [3] unused, then per thickness node the R' row then the T' row
// (kBssrdfTableR values each).
// Evaluation: optical thicknesses outside [kMultipoleTableDMin, kMultipoleTableDMax] are clamped to it (below 1/4 of
// a mean free path diffusion does not describe a sheet; at 64 the slab reflects as a half-space within 0.1%).
// Interpolation: linear between thickness nodes (at log d') and between radial bin centres. Geometric interpolation
// between thickness nodes follows transmittance's exponential fall through thick slabs better (8% at albedo 0.8 and
// 10 mean free paths, where under 1% of the light crosses) but made frames 30% longer on llvmpipe.
// The thick limit is the half-space with the light spread along the beam (photon beam diffusion's source), not the
// standard dipole's single source at one mean free path: their total reflectances agree within 2% at reduced albedo
// 0.99 and above, and the beam's is 6% higher at 0.95 and 22% at 0.8 (docs/models/multipole.md).
// Near field: within kMultipoleTableNearField reduced mean free paths of the entry point the rows hold the disk's
// mean (its power kept). The beam's shallowest sources make the exact profiles rise as 1/r there, about 50 times the
// standard dipole's peak; diffusion does not describe light at that scale, and where two faces meet (a fin's rim)
// entry and exit points come arbitrarily close on different faces, where no sampling cancels the peak: the fin of
// the leaderboard rendered its rim white.
// Geometry: the model is a flat slab. Which face a pair of points lies on, and how thick the slab is between them,
// come from the pair itself where it can tell: across = -n_i . n_o (1 on opposite faces) and the distance between
// the faces h = (x_o - x_i) . (n_o - n_i) / 2 (the slab's thickness for a pair on its two faces; negative for two
// faces looking at each other across air, such as a cavity's walls, which are not a slab). When h > 0, the pair
// reads T of a slab h thick at the lateral distance sqrt(|x_o - x_i|^2 - h^2), mixed with R by `across`, so that a
// surface that turns (a fin's rim, a sphere) goes over from one to the other continuously; otherwise R alone, at the
// distance |x_o - x_i|. Reflection cannot tell the thickness from the pair: R reads the material's thickness
// (BandMedium::thickness; 0: a half-space).
#ifndef LUCENT_BSSRDF_MULTIPOLE_TABLE_H
#define LUCENT_BSSRDF_MULTIPOLE_TABLE_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"
#include "bssrdf/medium.h"
#include "bssrdf/standard_dipole.h"
#include "bssrdf/tabulated.h"

LUCENT_SHADER_BEGIN

LUCENT_CONST float kMultipoleTableKey = 2.0f;  // the directory's g of a multipole table (no phase function has it)
LUCENT_CONST int kMultipoleTableD = 25;        // thickness nodes: 8 octaves, 3 per octave
LUCENT_CONST float kMultipoleTableDMin = 0.25f;  // reduced mean free paths
LUCENT_CONST float kMultipoleTableDMax = 64.0f;
LUCENT_CONST float kMultipoleTableNearField = 1.0f;  // reduced mean free paths (see above)
LUCENT_CONST int kMultipoleTableFloats = kBssrdfTableHeader + 2 * kMultipoleTableD * kBssrdfTableR;

// Optical thickness of node j.
LUCENT_INLINE float multipole_table_thickness(int j) {
  return kMultipoleTableDMin * exp2(float(j) / 3.0f);
}

// The table at `offset` with its header's constants.
LUCENT_INLINE BandTable multipole_table_at(int offset) {
  BandTable table;
  table.offset = offset;
  table.r_max = offset >= 0 ? bssrdf_table_value(offset) : 0.0f;
  table.inv_q = offset >= 0 ? bssrdf_table_value(offset + 1) : 0.0f;
  table.c1 = offset >= 0 ? bssrdf_table_value(offset + 2) : 0.0f;
  return table;
}

// bssrdf_table_r_coord with the table's constants: one logarithm.
LUCENT_INLINE float multipole_table_r_coord(BandTable table, float r) {
  float c0 = 0.5f * kBssrdfTableRMin;
  if (r <= c0) return 0.0f;
  if (r < table.c1) return (r - c0) / (table.c1 - c0);
  return 1.0f + log(r / table.c1) * table.inv_q;
}

// The row (0: R', 1: T') of thickness node j at radial coordinate u (bssrdf_table_r_coord), linear between bin centres.
LUCENT_INLINE float multipole_table_row(BandTable table, int j, int row, float u) {
  int base = table.offset + kBssrdfTableHeader + (2 * j + row) * kBssrdfTableR;
  int i0 = min(int(u), kBssrdfTableR - 1);
  int i1 = min(i0 + 1, kBssrdfTableR - 1);
  return mix(bssrdf_table_value(base + i0), bssrdf_table_value(base + i1), u - float(i0));
}

// (R', T') of `table` at optical thickness d' and reduced radial distances r'_R (same face) and r'_T (lateral, opposite
// face), per unit refracted power and reduced area.
LUCENT_INLINE vec2 multipole_table_profiles(BandTable table, float d, float r_R, float r_T) {
  float dc = clamp(3.0f * log2(max(d, kMultipoleTableDMin) / kMultipoleTableDMin), 0.0f, float(kMultipoleTableD - 1));
  int j0 = min(int(dc), kMultipoleTableD - 1);
  int j1 = min(j0 + 1, kMultipoleTableD - 1);
  float fj = dc - float(j0);
  vec2 RT = vec2(0.0f);
  if (r_R < table.r_max) {
    float u = multipole_table_r_coord(table, r_R);
    RT.x = mix(multipole_table_row(table, j0, 0, u), multipole_table_row(table, j1, 0, u), fj);
  }
  if (r_T < table.r_max) {
    float u = multipole_table_r_coord(table, r_T);
    RT.y = mix(multipole_table_row(table, j0, 1, u), multipole_table_row(table, j1, 1, u), fj);
  }
  return RT;
}

// S_d [1/length^2] for one band (see the geometry above). Like the other models, S_d = M / (pi (1 - 2 C1(1/eta)))
// with M the exitance per unit refracted power.
LUCENT_INLINE float multipole_table_Sd(BandMedium m, float eta, vec3 x_i, vec3 n_i, vec3 x_o, vec3 n_o) {
  BandTable table = m.table;
  if (table.offset < 0) table = multipole_table_at(bssrdf_table_offset(m.alpha_prime, kMultipoleTableKey, eta));
  if (table.offset < 0) return 0.0f;
  vec3 delta = x_o - x_i;
  float dist2 = dot(delta, delta);
  float h = 0.5f * dot(delta, n_o - n_i);
  float across = h > 0.0f ? clamp(-dot(n_i, n_o), 0.0f, 1.0f) : 0.0f;
  float R = 0.0f, T = 0.0f;
  if (across < 1.0f) {
    float d_R = m.thickness > 0.0f ? m.thickness * m.sigma_t_prime : kMultipoleTableDMax;
    R = multipole_table_profiles(table, d_R, sqrt(dist2) * m.sigma_t_prime, 1e30f).x;
  }
  if (across > 0.0f)
    T = multipole_table_profiles(table, h * m.sigma_t_prime, 1e30f, sqrt(max(dist2 - h * h, 0.0f)) * m.sigma_t_prime).y;
  return mix(R, T, across) * m.sigma_t_prime * m.sigma_t_prime * kInvPi * standard_dipole_exit_normalization(eta);
}

LUCENT_SHADER_END

#if defined(__cplusplus)
#include <vector>
namespace lucent {
// The table of one band medium (kMultipoleTableFloats floats; see above), from the beam profiles of multipole.h in
// double precision with `depth_steps` depths along the beam (clustered at both faces); deterministic.
std::vector<float> build_multipole_table(float alpha_prime, float eta, int depth_steps = 256);
// The totals the renderers' lookups carry (x: reflectance, y: transmittance, per refracted power) of a slab
// `optical_thickness` reduced mean free paths thick: the table's rows summed over their bins, interpolated between
// thickness nodes as the lookups are (0: the half-space). The table through the process's store.
glm::vec2 multipole_table_totals(float alpha_prime, float eta, float optical_thickness);
}  // namespace lucent
#endif

#endif
