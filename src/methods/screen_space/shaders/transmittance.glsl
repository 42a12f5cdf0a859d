// transmittance.glsl: light that crosses a thin part of a translucent object from behind (Jimenez et al. 2010,
// "Real-Time Realistic Skin Translucency"), as irradiance at a front surface point x, shaded like the blurred light
// entering x directly but not blurred itself: T(d) below is already the profile integrated over the back surface
// (blurring it again would spread it twice). The including shader includes common/frame.glsl and
// common/lights.glsl first; scenes with directional lights only compile without the point-light lookup
// (LUCENT_DIRECTIONAL_LIGHTS_ONLY, render/light_gbuffer.h).
//
// For each light whose light reaches x from behind (n . w_l <= 0, so x itself receives none of it), the light
// G-buffer layer framing the translucent objects holds, at x's texel, the first surface the light's ray toward x
// meets: the point x_i where that light enters the object, with its normal n_i. Nothing lies between it and the
// light (it is the first hit), so it needs no shadow test; when the first hit is another object, the light is
// blocked and gives nothing. The thickness crossed is d = (x_i - x) . w_l (the distance along the light's ray; the
// texel's offset across the ray drops out), and the light entering the back, F_t(eta, n_i . w_l) (n_i . w_l) E_l
// (E_l the light's irradiance at x_i), reaches x in the fraction T(d) of the method's profile
// (screen_space_profile_io.h):
//
//   E_back(x) = sum_l T(d_l) F_t(eta, n_i . w_l) (n_i . w_l) E_l(x_i)
//
// T is exact for a slab of uniform thickness lit uniformly on its back; on curved or uneven parts it is the usual
// local-slab approximation. The sign test is continuous across the terminator: where n . w_l -> 0 the light's ray
// enters next to x, at grazing incidence, so both terms vanish there.
#include "bssrdf/fresnel.h"
#include "methods/screen_space/screen_space_profile_io.h"

vec3 back_irradiance(int object, vec3 x, vec3 n, MaterialGPU material, int profile) {
  float eta = material.sigma_a.w;
  vec3 s = vec3(burley_scale(material.sigma_a.x, material.sigma_s.x, material.g.x, eta),
                burley_scale(material.sigma_a.y, material.sigma_s.y, material.g.y, eta),
                burley_scale(material.sigma_a.z, material.sigma_s.z, material.g.z, eta));
  int size = frame.light_counts.z;
  vec3 E = vec3(0.0f);
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    LightGPU light = frame.lights[l];
    vec3 w_l;
    light_incidence(light, x, w_l);
    if (dot(n, w_l) > 0.0f) continue;  // lit from the front: transmitted_irradiance() has it
    int layer;
    vec2 uv;
    if (int(light.position.w) == LUCENT_LIGHT_DIRECTIONAL) {
      layer = light.views.x;
      uv = view_coords(frame.light_views[layer], x).xy;
      if (any(lessThan(uv, vec2(0.0f))) || any(greaterThanEqual(uv, vec2(1.0f)))) continue;
    } else {
#if defined(LUCENT_DIRECTIONAL_LIGHTS_ONLY)
      continue;
#else
      if (!point_light_lookup(light, light.views.x, light.views.y, x - light.position.xyz, layer, uv)) continue;
#endif
    }
    ivec3 texel = ivec3(clamp(ivec2(uv * float(size)), ivec2(0), ivec2(size - 1)), layer);
    vec4 x_i = texelFetch(light_position, texel, 0);
    if (int(x_i.w) - 1 != object) continue;
    vec3 w_i;
    vec3 E_l = light_incidence(light, x_i.xyz, w_i);
    float cos_i = dot(texelFetch(light_normal, texel, 0).xyz, w_i);
    if (cos_i <= 0.0f) continue;
    float d = max(0.0f, dot(x_i.xyz - x, w_l));
    vec3 T = vec3(profile_transmittance(profile, s.x, d), profile_transmittance(profile, s.y, d),
                  profile_transmittance(profile, s.z, d));
    E += T * fresnel_transmittance(eta, cos_i) * cos_i * E_l;
  }
  return E;
}
