// environment.h: environment lighting from an equirectangular HDR map, as in Dal Corso et al. 2015, Section 4
// and Fig. 15: the map is turned into M representative directional lights (whose scattered radiosity is cached
// like any other light's), and the renderer adds specular reflection by looking the reflected ray up in the map
// and multiplying by the Fresnel reflectance.
//
// Directions and map coordinates follow src/lights/equirect.h (+y up; u = 0.5 at -z, 0.75 at +x; v = 0 on the
// top row, the zenith), shared with the shaders. Design notes and measured errors: docs/lights/environment.md.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/image.h"
#include "lucent/scene.h"

namespace lucent {

// An equirectangular radiance map, width = 2 x height, row-major with the top row (zenith) first. Radiance is
// in the scene's radiance unit (DirectionalLight::radiance is this unit times steradians).
struct EnvironmentMap {
  std::string source = "<memory>";  // file it came from, for messages
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> radiance;  // RGB, finite and non-negative
  const glm::vec3& at(int x, int y) const { return radiance[static_cast<std::size_t>(y) * width + x]; }
  glm::vec3& at(int x, int y) { return radiance[static_cast<std::size_t>(y) * width + x]; }
};

// Loads a .hdr (Radiance RGBE) or .exr file (alpha ignored). Throws lucent::Error naming the file when it is
// missing or unreadable, has another extension, is not twice as wide as high, or holds a negative, NaN or
// infinite value.
EnvironmentMap load_environment_map(const std::string& path);
// The same checks on an image in memory; `source` names it in messages.
EnvironmentMap environment_map_from_image(const ImageRGBA32F& image, const std::string& source);
ImageRGBA32F environment_map_to_image(const EnvironmentMap& map);  // alpha 1, e.g. for write_hdr / write_exr

// Integral of L over the sphere [radiance x sr], RGB; 4 pi L for a constant map.
glm::vec3 environment_power(const EnvironmentMap& map);
// Exact irradiance E(n) = integral of L(w) max(0, n.w) dw for each unit normal, summed over all pixels.
std::vector<glm::vec3> environment_irradiance(const EnvironmentMap& map, const std::vector<glm::vec3>& normals);

enum class EnvironmentSampling {
  // Debevec 2005 median cut in (u, v) with sin(theta) weighting: the most powerful region is split across its
  // angularly longest side into two halves of equal power until there are M regions.
  MedianCut,
  // Pharr and Humphreys: the luminance x sin(theta) piecewise-constant 2D distribution, stratified into M cells
  // of equal power in its primary sample space (rows of cells in v, cells in u within each row).
  Stratified,
  // Rectangles in (u, v) of least power-weighted directional variance, sum of L |w - c|^2 dw about each
  // region's centroid c: the costliest region is split, along u or v, where its halves' costs add up to least.
  VarianceCut,
  // The variance cut's centroids refined by 10 Lloyd iterations of weighted k-means on the sphere: the regions
  // become the Voronoi cells of the centroids (any shape, across the u seam too). The default.
  KMeans,
};

// At most M (>= 1) directional lights standing in for the map. The sphere is cut into M regions; each light
// shines from its region's luminance-weighted mean direction (DirectionalLight::direction is the direction the
// light travels, away from the region) with radiance = the region's integral of L dw, so the lights' radiances
// add up to environment_power(map). Regions without power give no light (an all-black map gives none).
// Deterministic. KMeans gave the lowest RMS irradiance error on a sky with a sun for M = 4..32 (3 to 7 times lower
// than MedianCut and Stratified, whose equal-power regions spend most lights on the sun) and on smooth maps from
// M = 12 on (docs/lights/environment.md).
std::vector<DirectionalLight> environment_to_directional_lights(
    const EnvironmentMap& map, int M, EnvironmentSampling sampling = EnvironmentSampling::KMeans);

// Irradiance the lights give a surface with unit normal n: sum of radiance_i max(0, n . -direction_i).
glm::vec3 directional_lights_irradiance(const std::vector<DirectionalLight>& lights, glm::vec3 normal);

// Unit directions spread evenly over the sphere (spherical Fibonacci lattice), for error measurements.
std::vector<glm::vec3> sphere_directions(int count);

// Relative error of the lights' irradiance against the exact one over a set of normals. Per normal the error is
// the largest over R, G, B of |E_lights - E| / max(E, 0.01 max_n E) (the floor keeps normals that see almost
// nothing from dominating); max and root-mean-square over the normals.
struct IrradianceError {
  double max_relative = 0.0;
  double rms_relative = 0.0;
};
IrradianceError irradiance_error(const std::vector<glm::vec3>& normals, const std::vector<glm::vec3>& exact,
                                 const std::vector<DirectionalLight>& lights);

// What the renderer uploads for the specular lookup: the map area-averaged down to at most max_width texels
// wide (an even number >= 2; maps that are already small enough are copied), RGB floats, top row first, ready
// for glTexImage2D(GL_RGB32F) and glGenerateMipmap (the box-filtered mips of an equirect map are a fair
// prefilter for blurrier lookups).
struct EnvironmentTexture {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;         // 3 floats per texel
  glm::vec3 mean_radiance{0.0f};  // solid-angle-weighted mean of L = environment_power / (4 pi), full map
};
EnvironmentTexture make_environment_texture(const EnvironmentMap& map, int max_width = 1024);

// Procedural maps for scenes, tests and measurements.
struct SkyDescription {
  int width = 256;                                                     // height = width / 2
  glm::vec3 to_sun = glm::normalize(glm::vec3(0.55f, 0.57f, -0.61f));  // unit direction toward the sun
  float sun_radius_deg = 2.0f;                                         // angular radius of the disc
  glm::vec3 sun_radiance{4000.0f, 3600.0f, 3000.0f};                   // radiance of the disc
  glm::vec3 zenith{0.25f, 0.45f, 1.0f};                                // sky radiance straight up
  glm::vec3 horizon{0.9f, 1.0f, 1.1f};                                 // sky radiance at the horizon
  glm::vec3 ground{0.45f, 0.32f, 0.2f};                                // radiance below the horizon (warm ground)
};
// A clear sky: a zenith-to-horizon gradient with a glow around the sun, an anti-aliased sun disc and a uniform
// warm ground below the horizon.
EnvironmentMap make_sky_environment(const SkyDescription& sky = {});
// A smooth map with no sharp features: L(w) = base (1 + 0.6 w_y + 0.3 w_x), base = (0.6, 0.7, 0.9).
EnvironmentMap make_gradient_environment(int width);
// A constant map.
EnvironmentMap make_constant_environment(int width, glm::vec3 radiance);

}  // namespace lucent
