// light_map.frag: the diffuse irradiance at a surface point, sum over the lights of E max(n . w_l, 0) times the
// shadow test, into the object's light map (rgb; a = 1 marks a covered texel).
#include "common/frame.glsl"
#include "common/lights.glsl"

in VertexData {
  vec3 position;
  vec3 normal;
} v_in;

layout(location = 0) out vec4 out_irradiance;

void main() {
  vec3 n = normalize(v_in.normal);
  vec3 E = vec3(0.0f);
  // loop bound: LUCENT_MAX_LIGHTS x 7 x 7; at most LUCENT_MAX_LIGHTS lights, each with at most 7 x 7 shadow taps
  for (int l = 0; l < frame.light_counts.x; ++l) {
    vec3 w_l;
    vec3 incident = light_incidence(frame.lights[l], v_in.position, w_l);
    float cos_l = dot(n, w_l);
    if (cos_l > 0.0f) E += incident * cos_l * light_visibility(l, v_in.position, n);
  }
  out_irradiance = vec4(E, 1.0f);
}
