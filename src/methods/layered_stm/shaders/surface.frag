// surface.frag: per camera pixel, the texture coordinates, the surface gradients of u and v (from screen-space
// derivatives of position and texture coordinates, so that they follow the mesh as it deforms) and the
// interpolated least-squares plane. A world offset d along the surface moves the texture coordinates by
// (d . grad u, d . grad v): the tangent-space projection of Norberg 2010, Section 2.1.2, with the tangent and
// bi-normal scaled to texture units per scene unit.
in VertexData {
  vec3 position;
  vec3 normal;
  vec2 uv;
  vec3 plane_normal;
  vec3 plane_point;
  flat float object_id;
} v_in;

layout(location = 0) out vec4 out_surface;
layout(location = 1) out vec4 out_gradient_u;
layout(location = 2) out vec4 out_gradient_v;
layout(location = 3) out vec4 out_plane_normal;
layout(location = 4) out vec4 out_plane_point;

void main() {
  vec3 n = normalize(v_in.normal);
  vec3 dp1 = dFdx(v_in.position), dp2 = dFdy(v_in.position);
  vec2 duv1 = dFdx(v_in.uv), duv2 = dFdy(v_in.uv);
  // g . dp1 = du1, g . dp2 = du2, g . n = 0:  g = (du1 (dp2 x n) + du2 (n x dp1)) / det(dp1, dp2, n).
  vec3 a = cross(dp2, n), b = cross(n, dp1);
  float det = dot(dp1, a);
  vec3 gu = vec3(0.0f), gv = vec3(0.0f);
  if (abs(det) > 1e-30f) {
    gu = (duv1.x * a + duv2.x * b) / det;
    gv = (duv1.y * a + duv2.y * b) / det;
  }
  out_surface = vec4(v_in.uv, v_in.object_id, 1.0f);
  out_gradient_u = vec4(gu, 0.0f);
  out_gradient_v = vec4(gv, 0.0f);
  out_plane_normal = vec4(v_in.plane_normal, 0.0f);
  out_plane_point = vec4(v_in.plane_point, 0.0f);
}
