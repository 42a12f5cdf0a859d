// gbuffer.frag: the texture-space G-buffer, step 3 of 3: keeps the texels whose square overlaps the triangle
// (separating axes: the bounding box, then each edge with the square's corner farthest inside) and writes the
// triangle's point nearest the texel centre; depth is that distance, so the nearest triangle wins a texel.
flat in vec2 g_texel[3];
flat in vec3 g_position[3];
flat in vec3 g_normal[3];
flat in float g_ratio;
flat in float g_object;

layout(location = 0) out vec4 out_position;      // xyz world [scene units], w: object index + 1
layout(location = 1) out vec4 out_normal_ratio;  // xyz world unit normal, w: +-A_S / A_T [scene units^2 per texel]

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

vec3 barycentric(vec2 a, vec2 b, vec2 c, vec2 p) {
  return vec3(cross2(c - b, p - b), cross2(a - c, p - c), cross2(b - a, p - a)) / cross2(b - a, c - a);
}

// Barycentric coordinates of the triangle's point nearest p.
vec3 nearest_barycentric(vec2 a, vec2 b, vec2 c, vec2 p) {
  vec3 l = barycentric(a, b, c, p);
  if (all(greaterThanEqual(l, vec3(0.0f)))) return l;
  vec2 corners[3] = vec2[3](a, b, c);
  float best = 1e30f;
  vec3 result = vec3(1.0f, 0.0f, 0.0f);
  for (int i = 0; i < 3; ++i) {
    vec2 s = corners[i], d = corners[(i + 1) % 3] - s;
    float s_t = clamp(dot(p - s, d) / max(dot(d, d), 1e-30f), 0.0f, 1.0f);
    float distance = length(s + s_t * d - p);
    if (distance < best) {
      best = distance;
      result = vec3(0.0f);
      result[i] = 1.0f - s_t;
      result[(i + 1) % 3] = s_t;
    }
  }
  return result;
}

void main() {
  vec2 p = gl_FragCoord.xy;  // texel centre [texels]
  vec2 lo = min(min(g_texel[0], g_texel[1]), g_texel[2]), hi = max(max(g_texel[0], g_texel[1]), g_texel[2]);
  if (any(greaterThan(lo, p + 0.5f)) || any(lessThan(hi, p - 0.5f))) discard;
  float orientation = sign(cross2(g_texel[1] - g_texel[0], g_texel[2] - g_texel[0]));
  for (int i = 0; i < 3; ++i) {
    vec2 a = g_texel[i], d = g_texel[(i + 1) % 3] - a;
    vec2 inward = orientation * vec2(-d.y, d.x);
    if (dot(inward, p - a) + 0.5f * (abs(inward.x) + abs(inward.y)) < 0.0f) discard;
  }
  vec3 l = nearest_barycentric(g_texel[0], g_texel[1], g_texel[2], p);
  vec2 nearest = l.x * g_texel[0] + l.y * g_texel[1] + l.z * g_texel[2];
  gl_FragDepth = clamp(0.25f * length(nearest - p), 0.0f, 1.0f);
  vec3 position = l.x * g_position[0] + l.y * g_position[1] + l.z * g_position[2];
  vec3 normal = normalize(l.x * g_normal[0] + l.y * g_normal[1] + l.z * g_normal[2]);
  out_position = vec4(position, g_object + 1.0f);
  // Only texels whose centre lies on the triangle carry its area (+A_S / A_T): a sum over texels is then the
  // midpoint rule of Chang et al.'s Eq. 7. Texels the triangle merely touches hold the nearest point for lookups
  // and -A_S / A_T.
  bool centre_inside = all(greaterThanEqual(barycentric(g_texel[0], g_texel[1], g_texel[2], p), vec3(0.0f)));
  gl_FragDepth = centre_inside ? 0.0f : gl_FragDepth;
  out_normal_ratio = vec4(normal, centre_inside ? g_ratio : -g_ratio);
}
