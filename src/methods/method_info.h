// method_info.h: a rendering method as data: its name, summary, parameters, passes and statistics. No GL: the
// scene parser, `lucent methods`, the docs and the CPU tools read it without a context. The method's GPU side
// (method.h) is created from it by create_method().
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "lucent/params.h"
#include "lucent/scene.h"

namespace lucent::texture_space {
struct AtlasOptions;
struct SceneAtlas;
}  // namespace lucent::texture_space

namespace lucent::methods {

// A GPU pass the method runs, timed and shown as a debug group under this name.
struct PassDecl {
  std::string_view name;
  std::string_view doc;
};

// A statistic the method reports each frame (lucent render's summary, --timings-json, bench, the viewer).
struct StatDecl {
  std::string_view name;
  std::string_view unit;  // "" when a count or a fraction
  std::string_view doc;
};

// What a method's precompute step sees: the scene as the GPU gets it (for needs_texture_atlas methods every
// translucent mesh replaced by its atlas mesh, texture coordinates set) and the atlas (null for other methods).
struct PrecomputeInput {
  const Scene& scene;
  const texture_space::SceneAtlas* atlas = nullptr;
};

// CPU preprocessing a method declares: run before its GPU side is created, its bytes cached in lucent::cache
// (src/cache/precompute_cache.h) and handed to create_method in MethodSetup::precomputed. The cache key
// (precompute_key in methods/precompute.h) is `kind`, `version`, the method's name and parameters, the scene's
// scale_mm, and each object's mesh, transform, material or albedo (and the atlas's size and chart ids): compute
// must depend on nothing else of the scene (lights, camera and render settings belong in the frames).
struct PrecomputeDecl {
  std::string_view kind;  // names the cache folder: letters, digits, '-', '_' and '.'
  std::uint32_t version = 1;  // bump whenever the bytes change for the same inputs (encoding or computation)
  // The bytes; `progress(fraction)` from 0 to 1 as work is done (the runner keeps what it reports in [0, 1] and
  // non-decreasing, and reports 1 at the end). Throws lucent::Error for inputs it cannot handle.
  std::vector<std::byte> (*compute)(const PrecomputeInput& input, const std::function<void(double)>& progress) = nullptr;
};

// Agreement a method promises with its reference (the bssrdf reference; volpath's for a method that estimates it)
// where methods are weakest: per pixel on the conformance sphere (about two transport mean free paths across), and
// on a thin slab lit from behind and a coarse box (eight vertices) lit obliquely. Each value is a relative error:
// `*_mean` of the mean radiance over the object's pixels, `*_pixels` the noise-corrected RMS error per pixel over
// the mean reference radiance (tests/gl/test_method_conformance.cpp). Each method declares them beside the values it
// measured.
struct ConformanceTolerances {
  double sphere_pixels = 1.0;
  double slab_mean = 1.0, slab_pixels = 1.0;
  double box_mean = 1.0, box_pixels = 1.0;
};

struct MethodInfo {
  std::string_view name;
  std::string_view summary;
  std::span<const ParamDecl> params;
  std::span<const PassDecl> passes;  // in frame order; a frame may skip some (e.g. a converged or solved state)
  std::span<const StatDecl> stats = {};
  // Parameters for a small, fast render (a JSON object merged into the scene's "method"): what the conformance
  // test (tests/gl/test_method_conformance.cpp) and CI use.
  std::string_view quick_settings = "{}";
  // Agreement the method promises with the bssrdf reference on the conformance scene with quick_settings:
  // relative error of the mean radiance over the object's pixels.
  double reference_tolerance = 0.25;
  bool needs_texture_atlas = false;  // texture-space methods: objects get an atlas, blob surfaces are refused
  // needs_texture_atlas: the atlas options from the method's parameters (null: AtlasOptions{}).
  texture_space::AtlasOptions (*atlas_options)(const ParamValues& params) = nullptr;
  const PrecomputeDecl* precompute = nullptr;  // null: the method precomputes nothing on the CPU
  // Textured materials (MaterialMaps): a method that does not read them is refused such a scene with one line,
  // rather than rendering the maps' mean.
  bool reads_material_maps = false;
  // The method estimates the image of the volpath reference itself (the physics, not a model of it): `lucent
  // reference --device gpu` renders references with it (render/gpu_reference.h).
  bool estimates_volpath = false;
  // needs_texture_atlas methods: the scene whose translucent meshes the atlas is built on and the GPU draws, made
  // from the scene as loaded (a method that needs other meshes, e.g. remeshed, makes and caches them itself);
  // null: the scene's own meshes. Throws lucent::Error for meshes the method cannot use.
  Scene (*prepare_meshes)(const Scene& scene, const std::function<void(double)>& progress) = nullptr;
  ConformanceTolerances weakest = {};  // the sphere per pixel, the backlit thin slab and the coarse box
};

// The registered method that estimates volpath's image (estimates_volpath), or null.
const MethodInfo* volpath_method();

// Every registered method (src/methods/method_list.h), the default first.
std::span<const MethodInfo* const> method_registry();
const MethodInfo* find_method(std::string_view name);
const MethodInfo& default_method();

// Throws lucent::Error("<scene>: /objects/<i>/material/<map key>: method '<name>' does not read textured
// materials; ...") for the first object whose material has maps.
void refuse_material_maps(const Scene& scene, const MethodInfo& method);

}  // namespace lucent::methods
