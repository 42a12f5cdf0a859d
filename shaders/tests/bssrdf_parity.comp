// bssrdf_parity.comp: evaluates the shared BSSRDF code for each test configuration (GPU parity test).
#include "shared/shader_io.h"
#include "bssrdf/model.h"

layout(local_size_x = 64) in;
layout(std430, binding = LUCENT_BINDING_PARITY) buffer Cases { ParityCaseGPU cases[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(cases.length())) return;
  ParityCaseGPU c = cases[i];
  float eta = c.sigma_a.w;
  vec3 S;
  for (int band = 0; band < 3; ++band) {
    BandMedium m = make_band_medium(c.sigma_a[band], c.sigma_s[band], c.g[band]);
    m.thickness = c.g.w;
    S[band] = bssrdf_Sd(int(c.sigma_s.w), m, eta, c.x_i.xyz, c.w_i.xyz, c.n_i.xyz, c.x_o.xyz, c.n_o.xyz);
  }
  cases[i].result.S_d = vec4(S, fresnel_transmittance(eta, dot(c.w_i.xyz, c.n_i.xyz)));
}
