// map_lookup.glsl: Algorithm 1 of Dal Corso et al. 2015: the scattered radiosity B at a surface point from the K
// maps, weighted by multi-sampled visibility (eps_bias), positions offset by eps_comb. Used by the combine pass,
// the VPL pass and the radiosity probes.
layout(binding = LUCENT_TEX_MAP_DEPTH) uniform sampler2DArray map_depth;
layout(binding = LUCENT_TEX_RADIOSITY) uniform sampler2DArray radiosity;

// Visible taps of the (2h+1)^2 neighbourhood of map k at t: a tap counts when x_bar is not behind the surface
// stored there (depth test with bias); its radiosity is the texel's mean over frames. Taps are tested
// individually so that a texel of an occluding surface never blends into x_o (bilinear filtering did, and drew
// bright seams where one object occludes another in a map view).
vec4 visible_taps(int k, vec3 t, float bias) {
  int size = method.counts.z;
  int h = method.vpls.z / 2;
  ivec2 center = ivec2(t.xy * float(size));
  vec3 sum = vec3(0.0f);
  float visible = 0.0f;
  // loop bound: LUCENT_MAX_MAPS x 7 x 7; visibility_taps <= 7, once per map (K <= LUCENT_MAX_MAPS)
  for (int dy = -h; dy <= h; ++dy)
    // loop bound: LUCENT_MAX_MAPS x 7 x 7; the taps of one row, counted with the loop above
    for (int dx = -h; dx <= h; ++dx) {
      ivec3 p = ivec3(clamp(center + ivec2(dx, dy), ivec2(0), ivec2(size - 1)), k);
      if (t.z > texelFetch(map_depth, p, 0).r + bias) continue;
      vec4 accumulated = texelFetch(radiosity, p, 0);
      if (accumulated.a <= 0.0f) continue;
      sum += accumulated.rgb / accumulated.a;
      visible += 1.0f;
    }
  return vec4(sum, visible) / float((2 * h + 1) * (2 * h + 1));
}

// Algorithm 1: scattered radiosity at x_o from the K maps; coverage in w (0 = seen by no map).
// filter_lod = 0: per-tap visibility and radiosity (visible_taps); filter_lod > 0: multi-sampled visibility
// and a mip-filtered look-up (the paper's noise filter), normalised by the filtered frame count.
vec4 combine_maps(vec3 x_o, vec3 n_o) {
  int size = method.counts.z;
  vec3 color = vec3(0.0f);
  float n = 0.0f;
  // loop bound: LUCENT_MAX_MAPS x 7 x 7; K <= LUCENT_MAX_MAPS maps, each with at most 7 x 7 visibility taps
  for (int k = 0; k < method.counts.x; ++k) {
    vec3 d_k = method.maps[k].direction.xyz;
    float texel_width = method.maps[k].direction.w / float(size);
    float cos_theta = clamp(dot(n_o, d_k), 0.0f, 1.0f);
    vec3 x_bar = x_o - method.biases.y * texel_width * (n_o - cos_theta * d_k);
    vec3 t = view_coords(method.maps[k], x_bar);
    if (any(lessThan(t.xy, vec2(0.0f))) || any(greaterThanEqual(t.xy, vec2(1.0f)))) continue;
    // Depth spans the view width, so eps_bias texels are eps_bias / size in depth units.
    float bias = method.biases.x / float(size);
    if (method.biases.z <= 0.0f) {
      vec4 taps = visible_taps(k, t, bias);
      color += taps.rgb;
      n += taps.w;
      continue;
    }
    float v = multisample_visibility(map_depth, t, k, size, bias, method.vpls.z);
    if (v <= 0.0f) continue;
    vec4 accumulated = textureLod(radiosity, vec3(t.xy, float(k)), method.biases.z);
    if (accumulated.a <= 0.0f) continue;
    color += v * accumulated.rgb / accumulated.a;  // mean over frames, normalised by filtered coverage
    n += v;
  }
  return n > 0.0f ? vec4(color / n, 1.0f) : vec4(0.0f);
}

