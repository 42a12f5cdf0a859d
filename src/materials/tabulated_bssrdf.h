// tabulated_bssrdf.h: the tables of the "tabulated" model (layout and evaluation: bssrdf/tabulated.h).
//
// A table is the exitance profile of a half-space of one band medium (albedo a = sigma_s / sigma_t, HG g, eta)
// over reduced distance, azimuth and incidence, computed by the photon transport of `lucent slab`
// (transport/slab.h: smooth Fresnel boundary with total internal reflection, the true phase function, all orders
// of scattering). Tables are dimensionless (reduced mean free paths), so a medium's table serves every scale.
//
// The process keeps one array of tables (directory + tables, the layout the shaders read): a table is built on
// first use of its medium, through the precompute cache (kind "bssrdf-table"), and never changes afterwards.
// C++ code reaches it through bssrdf_table_offset() (bssrdf/tabulated.h); the renderer uploads the array.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "lucent/material.h"

namespace lucent {

// Photons traced per incidence node of a table (the table has kBssrdfTableTheta nodes), by default.
inline constexpr std::uint64_t kBssrdfTablePhotons = 100000;
// Process-wide; tables built afterwards use it (tests use fewer photons; the count is part of the cache key).
void set_bssrdf_table_photons(std::uint64_t photons_per_node);
std::uint64_t bssrdf_table_photons();

struct BssrdfTableStats {
  double seconds = 0.0;         // build time (0 when read from the cache)
  bool from_cache = false;
  double total = 0.0;           // reflectance per refracted power at normal incidence, tail included
  double tail_fraction = 0.0;   // of that, the part leaving beyond r'_max (not in the table)
};

// Largest reduced radius a table of this medium covers: 25 diffusion lengths (exp(-25) of the profile), within
// [8, 4000] reduced mean free paths.
float bssrdf_table_r_max(float albedo, float g);

// The table of one band medium (kBssrdfTableFloats floats, bssrdf/tabulated.h), by photon transport with
// `photons_per_node` photons per incidence node; deterministic, on all cores.
std::vector<float> build_bssrdf_table(float albedo, float g, float eta, std::uint64_t photons_per_node,
                                      BssrdfTableStats* stats = nullptr);

// Outer edge of radial bin k of a table reaching r'_max (k = 0 .. kBssrdfTableR - 1; bin 0 starts at 0).
double bssrdf_table_radial_edge(int k, double r_max);
// Rescales a radial row of bin averages (kBssrdfTableR values) so that its interpolation between bin centres
// (bssrdf_table_r_coord) carries exactly the row's power.
void preserve_bssrdf_table_row_power(float* row, double r_max);

// Builds (or reads from the cache) the tables of every band of `material` when its model reads tables (Tabulated:
// the photon-transport half-space; Multipole: the slab profiles of bssrdf/multipole_table.h).
void prepare_bssrdf_tables(const Material& material);

// The array for the shaders' storage buffer: every table built so far, with the directory sorted by albedo and
// its unused entries at kBssrdfTableUnusedAlbedo (bssrdf/tabulated.h: the shaders' loop-free search). Throws
// lucent::Error when more than kBssrdfTableSameAlbedo band media share one albedo.
std::vector<float> bssrdf_table_array();
// Changes whenever a table is added (the renderer re-uploads the array).
std::uint64_t bssrdf_table_generation();
// Statistics of the most recent table added (for --verbose output and the documentation's measurements).
BssrdfTableStats last_bssrdf_table_stats();

}  // namespace lucent
