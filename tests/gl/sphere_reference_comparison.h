// sphere_reference_comparison.h: a texture-space method's image of the conformance sphere (skim-milk-like
// material, eta 1.3, lit from the side) against the CPU bssrdf reference of the same diffusion model, in the mean
// and per block of pixels.
#ifndef LUCENT_TESTS_GL_SPHERE_REFERENCE_COMPARISON_H
#define LUCENT_TESTS_GL_SPHERE_REFERENCE_COMPARISON_H
#include <string>

namespace lucent::test {

struct SphereComparison {
  double mean = 0.0, reference_mean = 0.0;
  double relative_mean_error = 0.0;  // (mean - reference_mean) / reference_mean, signed
  // Over the lit region, per block of 4 x 4 pixels wholly on the sphere whose reference exceeds a fifth of the
  // reference's mean over the sphere: the RMSE relative to the reference's mean over those blocks, the largest
  // |ours - reference| / reference, and the number of blocks.
  double relative_rmse = 0.0, max_relative = 0.0;
  int lit_blocks = 0;
};

// The conformance sphere's scene (JSON) at size x size pixels: `method_object` is the "method" object's content
// ("\"name\": \"hybrid\", \"N\": 64"), `model` the material's "model".
std::string sphere_scene_json(const std::string& method_object, const std::string& model, int size, int frames,
                              int seed);

// `method_keys`: the "method" object's keys besides "name"; `model`: the material's "model" ("standard",
// "directional"). Band means per pixel; the reference takes `reference_spp` samples per pixel.
SphereComparison compare_sphere_with_reference(const std::string& method, const std::string& method_keys,
                                               const std::string& model, int frames, int reference_spp);

// The comparison over 8 frames against a 1024-spp reference, printed, with the mean, the lit region's relative RMSE
// and its largest block error expected within the tolerances (gtest expectations).
void expect_sphere_agrees(const std::string& method, const std::string& method_keys, const std::string& model,
                          double mean_tolerance, double rmse_tolerance, double max_tolerance);

}  // namespace lucent::test

#endif
