// vpl_gather.glsl: emergent light of the translucent objects arriving at a diffuse surface point from the
// virtual point lights (Dal Corso et al. 2015, eq. 15 with the intensity of eq. 16), with the bounded geometry
// term and no visibility (the VPLs stand on the outermost surface, as in the paper).
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"

layout(std430, binding = LUCENT_BINDING_VPLS) readonly buffer VplBlock { VplGPU vpls[]; };

// Irradiance at x (normal n) from all VPLs. A VPL of area A_v emits radiance F_t(cos theta_v) B / pi, so
// E = sum F_t B / pi * A_v cos theta_v cos theta_x / d^2, with d^2 bounded below by A_v / pi (its footprint).
vec3 vpl_irradiance(vec3 x, vec3 n) {
  vec3 E = vec3(0.0f);
  // loop bound: param.vpls; the vpls parameter's range, once per shaded point
  for (int v = 0; v < method.vpls.x; ++v) {
    VplGPU vpl = vpls[v];
    float area = vpl.position.w;
    if (area <= 0.0f) continue;
    vec3 to_x = x - vpl.position.xyz;
    float d2 = dot(to_x, to_x);
    vec3 w = to_x * inversesqrt(max(d2, 1e-20f));
    float cos_v = dot(vpl.normal.xyz, w);
    float cos_x = -dot(n, w);
    if (cos_v <= 0.0f || cos_x <= 0.0f) continue;
    float G_b = cos_v * cos_x / max(d2, area * kInvPi);
    E += fresnel_transmittance(vpl.normal.w, cos_v) * kInvPi * vpl.radiosity.rgb * area * G_b;
  }
  return E;
}
