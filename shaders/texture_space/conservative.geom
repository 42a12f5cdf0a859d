// conservative.geom: the texture-space G-buffer, step 2 of 3: conservative rasterization without a driver
// extension. Each triangle becomes its texel-space bounding box grown by one texel (two triangles), which covers
// every texel whose square the triangle touches; gbuffer.frag keeps exactly those. The triangle itself goes to the
// fragments as flat values, with its area ratio A_S / A_T (Chang et al. 2008, Eqs. 6-7) [scene units^2 per texel].
layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

in CornerData {
  vec3 position;
  vec3 normal;
  vec2 uv;
  float object;
} corner[];

uniform float u_size;  // atlas width = height [texels]

flat out vec2 g_texel[3];     // corners [texels]
flat out vec3 g_position[3];  // corners, world [scene units]
flat out vec3 g_normal[3];    // corners, world
flat out float g_ratio;       // world area / atlas area [scene units^2 per texel]
flat out float g_object;      // scene object index

void main() {
  vec2 t0 = corner[0].uv * u_size, t1 = corner[1].uv * u_size, t2 = corner[2].uv * u_size;
  vec2 e1 = t1 - t0, e2 = t2 - t0;
  float texel_area = 0.5f * abs(e1.x * e2.y - e1.y * e2.x);
  if (texel_area <= 0.0f) return;
  float world_area = 0.5f * length(cross(corner[1].position - corner[0].position, corner[2].position - corner[0].position));
  vec2 lo = min(min(t0, t1), t2) - 1.0f, hi = max(max(t0, t1), t2) + 1.0f;
  vec2 box[4] = vec2[4](vec2(lo.x, lo.y), vec2(hi.x, lo.y), vec2(lo.x, hi.y), vec2(hi.x, hi.y));
  for (int i = 0; i < 4; ++i) {
    g_texel = vec2[3](t0, t1, t2);
    g_position = vec3[3](corner[0].position, corner[1].position, corner[2].position);
    g_normal = vec3[3](corner[0].normal, corner[1].normal, corner[2].normal);
    g_ratio = world_area / texel_area;
    g_object = corner[0].object;
    gl_Position = vec4(box[i] / u_size * 2.0f - 1.0f, 0.0f, 1.0f);
    EmitVertex();
  }
  EndPrimitive();
}
