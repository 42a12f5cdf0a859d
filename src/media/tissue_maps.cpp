// tissue_maps.cpp: procedural tissue layer maps and their image files (tissue_maps.h).
#include "media/tissue_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent::media {
namespace {

std::uint32_t hash3(int x, int y, int salt) {
  std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8DA6B343u + static_cast<std::uint32_t>(y) * 0xD8163841u +
                    static_cast<std::uint32_t>(salt) * 0xCB1AB31Fu + 0x68E31DA4u;
  h ^= h >> 16u;
  h *= 0x7FEB352Du;
  h ^= h >> 15u;
  h *= 0x846CA68Bu;
  h ^= h >> 16u;
  return h;
}
float lattice(int x, int y, int period, int salt) {
  x = ((x % period) + period) % period, y = ((y % period) + period) % period;
  return static_cast<float>(hash3(x, y, salt) >> 8u) / 16777216.0f;
}

// Value noise in [0, 1) with `period` lattice cells over [0, 1) (periodic).
float value_noise(float u, float v, int period, int salt) {
  const float x = u * static_cast<float>(period), y = v * static_cast<float>(period);
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  float tx = x - fx, ty = y - fy;
  tx = tx * tx * (3.0f - 2.0f * tx), ty = ty * ty * (3.0f - 2.0f * ty);
  const float a = lattice(ix, iy, period, salt), b = lattice(ix + 1, iy, period, salt);
  const float c = lattice(ix, iy + 1, period, salt), d = lattice(ix + 1, iy + 1, period, salt);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

// Four octaves, in [0, 1).
float fbm(float u, float v, int period, int salt) {
  float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
  for (int octave = 0; octave < 4; ++octave) {
    sum += amplitude * value_noise(u, v, period << octave, salt + octave);
    norm += amplitude;
    amplitude *= 0.5f;
  }
  return sum / norm;
}

// Distance to the nearest feature point of a periodic jittered grid of `cells` x `cells` cells (in cell units) and
// that point's random radius in [0.25, 0.5).
float cellular(float u, float v, int cells, int salt, float* radius) {
  const float x = u * static_cast<float>(cells), y = v * static_cast<float>(cells);
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  float best = 1e9f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int cx = ix + dx, cy = iy + dy;
      const float px = static_cast<float>(cx) + 0.15f + 0.7f * lattice(cx, cy, cells, salt);
      const float py = static_cast<float>(cy) + 0.15f + 0.7f * lattice(cx, cy, cells, salt + 1);
      const float d = std::hypot(x - px, y - py);
      if (d < best) best = d, *radius = 0.25f + 0.25f * lattice(cx, cy, cells, salt + 2);
    }
  return best;
}

// Round blobs in 70% of the cells of a periodic jittered grid, radius 0.3-0.6 cells: the largest of their height
// profiles sqrt(1 - (d / R)^2) (overlapping blobs merge instead of being cut along cell borders).
float blobs(float u, float v, int cells, int salt) {
  const float x = u * static_cast<float>(cells), y = v * static_cast<float>(cells);
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  float height = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int cx = ix + dx, cy = iy + dy;
      const float px = static_cast<float>(cx) + 0.15f + 0.7f * lattice(cx, cy, cells, salt);
      const float py = static_cast<float>(cy) + 0.15f + 0.7f * lattice(cx, cy, cells, salt + 1);
      if (lattice(cx, cy, cells, salt + 3) > 0.7f) continue;  // some cells have none
      const float r = 0.3f + 0.3f * lattice(cx, cy, cells, salt + 2);
      const float q = std::hypot(x - px, y - py) / r;
      height = std::max(height, std::sqrt(std::max(0.0f, 1.0f - q * q)));
    }
  return height;
}

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

ImageRGBA32F tissue_layer_maps(int size) {
  ImageRGBA32F image;
  image.width = image.height = size;
  image.pixels.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
      const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
      // Pores: small pits in the outer layer.
      float pore_radius = 0.0f;
      const float pore = cellular(u, v, 24, 11, &pore_radius);
      const float outer = 0.12f + 0.03f * (fbm(u, v, 8, 3) - 0.5f) - 0.07f * (1.0f - smoothstep(0.0f, 0.6f * pore_radius, pore));
      // Fat: blobs of random size, thickest at their centres.
      const float fat = 0.3f * blobs(u + 0.05f * fbm(u, v, 4, 21), v, 6, 17);
      // Vessels: ridges of domain-warped noise.
      const float wu = u + 0.08f * (fbm(u, v, 4, 31) - 0.5f), wv = v + 0.08f * (fbm(u, v, 4, 37) - 0.5f);
      const float ridge = 1.0f - std::fabs(2.0f * fbm(wu, wv, 4, 41) - 1.0f);
      const float vessel = 0.12f * smoothstep(0.95f, 0.985f, ridge);
      float* p = image.at(x, y);
      p[0] = std::max(outer, 0.02f);
      p[1] = fat;
      p[2] = vessel;
      p[3] = std::max(0.0f, 1.0f - (p[0] + p[1] + p[2]));
    }
  return image;
}

ImageRGBA32F uniform_layer_maps(float t0, float t1, float t2, float t3) {
  ImageRGBA32F image;
  image.width = image.height = 1;
  image.pixels = {t0, t1, t2, t3};
  return image;
}

ImageRGBA32F read_layer_maps(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  ImageRGBA32F image;
  if (ext == ".exr") {
    image = read_exr(path);
  } else if (ext == ".png") {
    const ImageRGBA8 bytes = read_png(path);
    image.width = bytes.width, image.height = bytes.height;
    image.pixels.resize(bytes.pixels.size());
    for (std::size_t i = 0; i < bytes.pixels.size(); ++i) image.pixels[i] = static_cast<float>(bytes.pixels[i]) / 255.0f;
  } else {
    throw Error(fmt::format("{}: layer maps must be a .png or .exr file", path));
  }
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    if (!std::isfinite(image.pixels[i]) || image.pixels[i] < 0.0f)
      throw Error(fmt::format("{}: texel {} channel {}: thickness {} is negative or not finite", path, i / 4, i % 4,
                              image.pixels[i]));
  return image;
}

TissueSurfaceTextures tissue_surface_textures(int size) {
  const ImageRGBA32F stack = tissue_layer_maps(size);
  TissueSurfaceTextures t;
  for (ImageRGBA32F* image : {&t.outer_base, &t.outer_normal, &t.inner_base}) {
    image->width = image->height = size;
    image->pixels.assign(stack.pixels.size(), 1.0f);
  }
  // Relief of the outer surface: the outer layer's thickness plus a little of the fat beneath.
  auto height = [&](int x, int y) {
    const float* p = stack.at(((x % size) + size) % size, ((y % size) + size) % size);
    return p[0] + 0.3f * p[1];
  };
  const float texel = 1.0f / static_cast<float>(size), relief = 0.02f;  // relief height in texture units
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float* p = stack.at(x, y);
      const float outer = p[0], fat = p[1], vessel = p[2];
      const float fat_weight = std::min(1.0f, fat / 0.15f), vessel_weight = std::min(1.0f, vessel / 0.06f);
      float* base = t.outer_base.at(x, y);
      const float pore = std::clamp((outer - 0.05f) / 0.07f, 0.0f, 1.0f);  // 0 in a pore
      const float skin = 1.0f - 0.15f * (1.0f - pore);  // pores darker
      base[0] = skin * (0.80f + 0.12f * fat_weight);
      base[1] = skin * (0.62f + 0.12f * fat_weight);
      base[2] = skin * (0.55f - 0.15f * fat_weight);
      base[3] = std::clamp(0.85f * pore * (1.0f - 0.5f * fat_weight), 0.0f, 1.0f);
      // Normal from central differences of the relief (texture units): n = (-dh/du, -dh/dv, 1) normalised.
      const float du = (height(x + 1, y) - height(x - 1, y)) * relief / (2.0f * texel);
      // Image rows run top to bottom, v bottom to top.
      const float dv = (height(x, y - 1) - height(x, y + 1)) * relief / (2.0f * texel);
      const float length = std::sqrt(du * du + dv * dv + 1.0f);
      float* n = t.outer_normal.at(x, y);
      n[0] = -du / length, n[1] = -dv / length, n[2] = 1.0f / length;
      float* inner = t.inner_base.at(x, y);
      inner[0] = 0.75f * (1.0f - 0.55f * vessel_weight) + 0.1f * fat_weight;
      inner[1] = 0.22f * (1.0f - 0.7f * vessel_weight) + 0.15f * fat_weight;
      inner[2] = 0.2f * (1.0f - 0.4f * vessel_weight) + 0.05f * fat_weight;
    }
  return t;
}

}  // namespace lucent::media
