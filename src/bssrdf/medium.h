// medium.h: derived optical quantities of a homogeneous medium for one colour band.
//
// Inputs per band: sigma_a, sigma_s (unreduced) and Henyey-Greenstein g, in inverse length units (the
// caller chooses mm^-1 or scene units^-1 consistently). Definitions as in Jensen et al. 2001 and
// Frisvad et al. 2014: sigma_s' = sigma_s (1 - g), sigma_t' = sigma_a + sigma_s', alpha' = sigma_s'/sigma_t',
// D = 1/(3 sigma_t'), sigma_tr = sqrt(3 sigma_a sigma_t') (Dal Corso et al. 2015, eq. 10).
#ifndef LUCENT_BSSRDF_MEDIUM_H
#define LUCENT_BSSRDF_MEDIUM_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

// Where a band medium's table lies in the BSSRDF table buffer (the multipole model's, bssrdf/multipole_table.h) and the
// constants of its radial coordinate, read once per band medium: each read of the buffer per evaluation cost the
// radiosity-maps integration about 3% of its time on llvmpipe.
struct BandTable {
  int offset;   // first float of the table; -1: not looked up (evaluations search the directory)
  float r_max;  // largest reduced radius in the table
  float inv_q;  // 1 / log of the radial bins' edge ratio
  float c1;     // centre of radial bin 1
};

struct BandMedium {
  float sigma_a;        // absorption coefficient [1/length]
  float sigma_s;        // scattering coefficient, unreduced [1/length]
  float g;              // Henyey-Greenstein mean cosine [-1, 1]
  float sigma_s_prime;  // reduced scattering sigma_s (1 - g) [1/length]
  float sigma_t_prime;  // reduced extinction [1/length]
  float sigma_t;        // extinction sigma_a + sigma_s [1/length]
  float alpha_prime;    // reduced single-scattering albedo [0, 1]
  float D;              // classical diffusion coefficient 1/(3 sigma_t') [length]
  float sigma_tr;       // effective transport coefficient [1/length]
  float thickness;      // the multipole model's slab thickness [length]; 0: a half-space (every other model)
  BandTable table;      // the multipole model's table
};

LUCENT_INLINE BandMedium make_band_medium(float sigma_a, float sigma_s, float g) {
  BandMedium m;
  m.sigma_a = sigma_a;
  m.sigma_s = sigma_s;
  m.g = g;
  m.sigma_s_prime = sigma_s * (1.0f - g);
  m.sigma_t_prime = sigma_a + m.sigma_s_prime;
  m.sigma_t = sigma_a + sigma_s;
  m.alpha_prime = m.sigma_s_prime / m.sigma_t_prime;
  m.D = 1.0f / (3.0f * m.sigma_t_prime);
  m.sigma_tr = sqrt(3.0f * sigma_a * m.sigma_t_prime);
  m.thickness = 0.0f;
  m.table.offset = -1;
  m.table.r_max = m.table.inv_q = m.table.c1 = 0.0f;
  return m;
}

LUCENT_SHADER_END

#endif
