// image_region.cpp: see image_region.h.
#include "reference/image_region.h"

#include <cmath>

#include <fmt/format.h>

#include "image/image_metrics.h"
#include "lucent/error.h"
#include "reference/embree_scene.h"
#include "reference/reference_renderer.h"

namespace lucent::reference {

std::vector<std::uint8_t> region_mask(const Scene& scene, const ImageRegion& region) {
  int object = -1;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].name == region.object) object = static_cast<int>(i);
  if (object < 0) throw Error(fmt::format("region '{}': the scene has no object named '{}'", region.name, region.object));
  const EmbreeScene rt(scene);
  const int width = scene.render.width, height = scene.render.height;
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      glm::dvec3 origin, direction;
      camera_ray(scene.camera, width, height, x + 0.5, y + 0.5, origin, direction);
      const SurfaceHit hit = rt.intersect(origin, direction, 1e30, 0.0);
      if (hit.object != object) continue;
      const double r = glm::length(hit.position - region.center);
      if (r <= region.radius && r >= region.min_radius) mask[static_cast<std::size_t>(y) * width + x] = 1;
    }
  return mask;
}

RegionMean region_mean(const ImageRGBA32F& image, const std::vector<std::uint8_t>& mask, float exposure,
                       const ImageRGBA32F* standard_error) {
  if (mask.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) ||
      (standard_error && (standard_error->width != image.width || standard_error->height != image.height)))
    throw Error(fmt::format("region mean: the image ({}x{}) and the mask ({} pixels) differ in size", image.width,
                            image.height, mask.size()));
  const ImageRGBA8 display = to_display(image, exposure);
  RegionMean m;
  glm::dvec3 variance(0.0);
  double display_sum = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    ++m.pixels;
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 4 * i + static_cast<std::size_t>(c);
      m.mean[c] += image.pixels[k];
      display_sum += display.pixels[k];
      if (standard_error) variance[c] += double(standard_error->pixels[k]) * standard_error->pixels[k];
    }
  }
  if (m.pixels == 0) return m;
  const double n = m.pixels;
  m.mean /= n;
  m.standard_error = glm::sqrt(variance) / n;  // pixels' errors are independent (their own samples)
  m.display = display_sum / (3.0 * n);
  return m;
}

}  // namespace lucent::reference
