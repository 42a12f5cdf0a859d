// equirect.h: the equirectangular (latitude-longitude) mapping between directions and environment-map
// coordinates, shared by the C++ light extraction (src/lights/) and the shaders' specular lookup.
//
// Convention (world space, +y up):
//   theta = polar angle from +y in [0, pi];  phi = azimuth from -z toward +x in (-pi, pi].
//   u = 0.5 + phi / (2 pi)   u = 0.5 at -z (the centre of the image is what a camera looking along -z sees
//                            behind the scene), 0.75 at +x, 0.25 at -x, 0 and 1 at +z; u grows to the right
//                            when seen from inside, so the map is not mirrored.
//   v = theta / pi           v = 0 is the top row of the image (zenith, +y), v = 1 the bottom row (nadir, -y).
//   direction(u, v) = (sin theta sin phi, cos theta, -sin theta cos phi).
// Pixel (x, y) of a W x H map (row 0 on top, W = 2H) covers u in [x, x+1) / W and v in [y, y+1) / H; its
// centre is at ((x + 0.5) / W, (y + 0.5) / H) and its solid angle is exactly
//   d_omega(y) = (2 pi / W) (cos theta_top - cos theta_bottom)   (= (2 pi / W)(pi / H) sin theta, to first order),
// so the solid angles of all pixels sum to 4 pi.
// In GL, upload the rows in memory order (row 0 first) and sample with texcoord (u, v) = equirect_uv(direction):
// t = 0 is then the top row. Wrap u with GL_REPEAT and clamp v to the edge.
#ifndef LUCENT_LIGHTS_EQUIRECT_H
#define LUCENT_LIGHTS_EQUIRECT_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"

LUCENT_SHADER_BEGIN

// Unit direction at map coordinates uv in [0, 1]^2.
LUCENT_INLINE vec3 equirect_direction(vec2 uv) {
  float phi = kTwoPi * (uv.x - 0.5f);
  float theta = kPi * uv.y;
  float sin_theta = sin(theta);
  return vec3(sin_theta * sin(phi), cos(theta), -sin_theta * cos(phi));
}

// Map coordinates of a unit direction: u in [0, 1], v in [0, 1]. At the poles (no azimuth) u is 0.5.
LUCENT_INLINE vec2 equirect_uv(vec3 direction) {
  float phi = abs(direction.x) + abs(direction.z) > 0.0f ? atan(direction.x, -direction.z) : 0.0f;
  float theta = acos(clamp(direction.y, -1.0f, 1.0f));
  return vec2(0.5f + phi * (0.5f * kInvPi), theta * kInvPi);
}

// Unit direction through the centre of pixel (x, y) of a width x height map.
LUCENT_INLINE vec3 equirect_pixel_direction(int x, int y, int width, int height) {
  return equirect_direction(vec2((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)));
}

// Solid angle [sr] of any pixel in row y of a width x height map (exact for the pixel's spherical rectangle).
// cos a - cos b is written as 2 sin((a + b) / 2) sin((b - a) / 2), which keeps float precision at the poles.
LUCENT_INLINE float equirect_pixel_solid_angle(int y, int width, int height) {
  float theta_centre = kPi * (float(y) + 0.5f) / float(height);
  float half_row = 0.5f * kPi / float(height);
  return kTwoPi / float(width) * 2.0f * sin(theta_centre) * sin(half_row);
}

LUCENT_SHADER_END

#endif
