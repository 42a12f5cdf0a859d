// tabulated.h: the "tabulated" BSSRDF model: the half-space profile of the medium itself, computed by photon
// transport (src/materials/tabulated_bssrdf.cpp, the transport of `lucent slab`) and read from a table.
//
// What the table holds, per band medium (single-scattering albedo a = sigma_s / sigma_t, Henyey-Greenstein g, eta):
// the exitance M of a half-space behind a smooth boundary, per unit refracted power and unit area, at the exit
// point's distance r from the entry point and azimuth phi (0: ahead, in the refracted beam's direction of travel),
// for a beam arriving at polar angle theta_i outside. All orders of scattering, total internal reflection and
// the medium's true phase function are in it; nothing is fitted. Lengths are reduced mean free paths
// (r' = r sigma_t'), so one table serves every scale of the same medium: M(r) = sigma_t'^2 M'(r sigma_t').
// Like the other models, S_d = M / (pi (1 - 2 C1(1/eta))) (the exit normalisation of better_dipole.h), so that
// S = T12(w_i) S_d T21(w_o) leaves exactly M; the flat total is the transport's reflectance per refracted power.
//
// Layout (one float array, the same in C++ and in the shaders' storage buffer LUCENT_BINDING_BSSRDF_TABLES):
//   [0]                          number of tables
//   [1 + 4k .. 4 + 4k]           directory entry k < kBssrdfTableCapacity: a, g, eta, first float of its table
//   table: [0] r'_max, [1..3] unused, then kBssrdfTableTheta x kBssrdfTablePhi x kBssrdfTableR values
//          (theta outermost, r innermost).
// Radial bins: [0, r'_min], then kBssrdfTableR - 1 bins with logarithmically spaced edges from r'_min to r'_max.
// Azimuth: kBssrdfTablePhi equal bins over [0, pi] (the profile is symmetric about the plane of incidence).
// Incidence: kBssrdfTableTheta nodes from 0 to kBssrdfTableThetaMaxDeg degrees. Values are bin averages,
// interpolated linearly between bin centres (log radius), azimuth bins and incidence nodes.
//
// Where the table comes from: C++ provides bssrdf_table_offset() (finds or builds the medium's table, through the
// precompute cache) and bssrdf_table_value(); the shaders search the directory of the buffer the renderer
// uploads (render/scene_gpu.cpp), which holds every table the scene's materials need. In that buffer the directory
// is sorted by albedo and its unused entries hold albedo kBssrdfTableUnusedAlbedo, so the shaders find an entry by
// a binary search of fixed length written without a loop: a directory loop per BSSRDF sample exceeded llvmpipe's
// cap of 65535 loop iterations per invocation (per-pixel at N 4096 with 7 or more tables read zeros, silently).
#ifndef LUCENT_BSSRDF_TABULATED_H
#define LUCENT_BSSRDF_TABULATED_H
#include "shared/bridge.h"
#include "shared/bindings.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"
#include "bssrdf/medium.h"

#define LUCENT_BSSRDF_TABLE_CAPACITY 64  // a power of two: the shaders' binary search halves it 6 times

LUCENT_SHADER_BEGIN

LUCENT_CONST int kBssrdfTableCapacity = LUCENT_BSSRDF_TABLE_CAPACITY;
LUCENT_CONST int kBssrdfTableR = 64;
LUCENT_CONST int kBssrdfTablePhi = 12;
LUCENT_CONST int kBssrdfTableTheta = 8;
LUCENT_CONST float kBssrdfTableThetaMaxDeg = 84.0f;
LUCENT_CONST float kBssrdfTableRMin = 0.02f;  // reduced mean free paths
LUCENT_CONST int kBssrdfTableHeader = 4;
LUCENT_CONST int kBssrdfTableDirectory = 1 + 4 * LUCENT_BSSRDF_TABLE_CAPACITY;
LUCENT_CONST float kBssrdfTableUnusedAlbedo = 3.0e38f;  // unused directory entries of the uploaded buffer
LUCENT_CONST int kBssrdfTableSameAlbedo = 4;  // entries whose albedo matches within 1e-5 (other g or eta) searched
LUCENT_CONST int kBssrdfTableFloats = kBssrdfTableHeader + kBssrdfTableTheta * kBssrdfTablePhi * kBssrdfTableR;

LUCENT_SHADER_END

#if defined(__cplusplus)
namespace lucent::shader {
// The first float of the table of (albedo, g, eta), built on first use (thread-safe); see tabulated_bssrdf.h.
int bssrdf_table_offset(float albedo, float g, float eta);
// Value i of the process's table array.
float bssrdf_table_value(int i);
}  // namespace lucent::shader
#else
layout(std430, binding = LUCENT_BINDING_BSSRDF_TABLES) readonly buffer BssrdfTableBlock { float bssrdf_tables[]; };
float bssrdf_table_value(int i) { return bssrdf_tables[i]; }
// Directory search; -1 when the renderer uploaded no table for this medium (it always does for its materials).
float bssrdf_table_albedo(int k) { return bssrdf_tables[1 + 4 * k]; }
// The table offset of directory entry k when it is the medium (albedo within 1e-5 relative, g and eta within 1e-6).
int bssrdf_table_match(int k, float albedo, float g, float eta) {
  if (k >= kBssrdfTableCapacity) return -1;
  int e = 1 + 4 * k;
  bool same = abs(bssrdf_tables[e] - albedo) <= 1e-5f * albedo && abs(bssrdf_tables[e + 1] - g) <= 1e-6f &&
              abs(bssrdf_tables[e + 2] - eta) <= 1e-6f;
  return same ? int(bssrdf_tables[e + 3]) : -1;
}
// Binary search of the sorted directory without a loop (see above): the first entry whose albedo is at least
// albedo (1 - 1e-5), then the kBssrdfTableSameAlbedo entries from there checked for g and eta as well.
int bssrdf_table_offset(float albedo, float g, float eta) {
  float key = albedo - 1e-5f * albedo;
  int i = 0;
  if (bssrdf_table_albedo(i + 31) < key) i += 32;
  if (bssrdf_table_albedo(i + 15) < key) i += 16;
  if (bssrdf_table_albedo(i + 7) < key) i += 8;
  if (bssrdf_table_albedo(i + 3) < key) i += 4;
  if (bssrdf_table_albedo(i + 1) < key) i += 2;
  if (bssrdf_table_albedo(i) < key) i += 1;
  int found = bssrdf_table_match(i, albedo, g, eta);
  if (found < 0) found = bssrdf_table_match(i + 1, albedo, g, eta);
  if (found < 0) found = bssrdf_table_match(i + 2, albedo, g, eta);
  if (found < 0) found = bssrdf_table_match(i + 3, albedo, g, eta);
  return found;
}
#endif

LUCENT_SHADER_BEGIN

// Continuous bin coordinate of reduced radius r' (bin centres at integers; log spacing beyond bin 0).
LUCENT_INLINE float bssrdf_table_r_coord(float r, float r_max) {
  float q = log(r_max / kBssrdfTableRMin) / float(kBssrdfTableR - 1);  // log of the edge ratio
  float c1 = kBssrdfTableRMin * exp(0.5f * q);                         // centre of bin 1 (geometric)
  float c0 = 0.5f * kBssrdfTableRMin;
  if (r <= c0) return 0.0f;
  if (r < c1) return (r - c0) / (c1 - c0);
  return 1.0f + log(r / c1) / q;
}

// Bin-averaged M' of the table at `offset` for incidence node t, azimuth bin p, radial coordinate u (linear in r).
LUCENT_INLINE float bssrdf_table_radial(int offset, int t, int p, float u) {
  int base = offset + kBssrdfTableHeader + (t * kBssrdfTablePhi + p) * kBssrdfTableR;
  int i0 = min(int(u), kBssrdfTableR - 1);
  int i1 = min(i0 + 1, kBssrdfTableR - 1);
  float f = u - float(i0);
  return mix(bssrdf_table_value(base + i0), bssrdf_table_value(base + i1), f);
}

// M' [per unit refracted power per reduced area] at reduced distance r, azimuth phi [0, pi], incidence theta_deg.
LUCENT_INLINE float bssrdf_table_exitance(int offset, float r, float phi, float theta_deg) {
  float r_max = bssrdf_table_value(offset);
  if (r >= r_max) return 0.0f;
  float u = bssrdf_table_r_coord(r, r_max);
  float pc = clamp(phi / (kPi / float(kBssrdfTablePhi)) - 0.5f, 0.0f, float(kBssrdfTablePhi - 1));
  int p0 = int(pc);
  int p1 = min(p0 + 1, kBssrdfTablePhi - 1);
  float fp = pc - float(p0);
  float tc = clamp(theta_deg / (kBssrdfTableThetaMaxDeg / float(kBssrdfTableTheta - 1)), 0.0f,
                   float(kBssrdfTableTheta - 1));
  int t0 = int(tc);
  int t1 = min(t0 + 1, kBssrdfTableTheta - 1);
  float ft = tc - float(t0);
  float a = mix(bssrdf_table_radial(offset, t0, p0, u), bssrdf_table_radial(offset, t0, p1, u), fp);
  float b = mix(bssrdf_table_radial(offset, t1, p0, u), bssrdf_table_radial(offset, t1, p1, u), fp);
  return mix(a, b, ft);
}

// S_d(x_i, w_i; x_o) [1/length^2] for one band. w_i points toward the light; the distance is |x_o - x_i| and the
// azimuth is measured in the tangent plane at x_i from the refracted beam's horizontal direction of travel.
LUCENT_INLINE float tabulated_Sd(BandMedium m, float eta, vec3 x_i, vec3 w_i, vec3 n_i, vec3 x_o) {
  int offset = bssrdf_table_offset(m.sigma_s / m.sigma_t, m.g, eta);
  if (offset < 0) return 0.0f;
  vec3 d = x_o - x_i;
  float r = length(d) * m.sigma_t_prime;
  float cos_i = clamp(dot(n_i, w_i), 0.0f, 1.0f);
  float theta_deg = degrees(acos(cos_i));
  vec3 travel = n_i * cos_i - w_i;  // horizontal part of the incoming direction of travel
  vec3 d_t = d - n_i * dot(d, n_i);
  float lt = length(travel), ld = length(d_t);
  float cos_phi = (lt > 1e-6f && ld > 1e-9f) ? clamp(dot(travel, d_t) / (lt * ld), -1.0f, 1.0f) : 1.0f;
  float M = bssrdf_table_exitance(offset, r, acos(cos_phi), theta_deg);
  return M * m.sigma_t_prime * m.sigma_t_prime * kInvPi / (4.0f * fresnel_c_phi(1.0f / eta));
}

LUCENT_SHADER_END

#endif
