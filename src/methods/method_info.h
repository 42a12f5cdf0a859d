// method_info.h: a rendering method as data: its name, summary, parameters, passes and statistics. No GL: the
// scene parser, `lucent methods`, the docs and the CPU tools read it without a context. The method's GPU side
// (method.h) is created from it by create_method().
#pragma once
#include <span>
#include <string_view>

#include "lucent/params.h"

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

struct MethodInfo {
  std::string_view name;
  std::string_view summary;
  std::span<const ParamDecl> params;
  std::span<const PassDecl> passes;  // in frame order; a frame may skip some (e.g. a converged or solved state)
  std::span<const StatDecl> stats;
  // Parameters for a small, fast render (a JSON object merged into the scene's "method"): what the conformance
  // test (tests/gl/test_method_conformance.cpp) and CI use.
  std::string_view quick_settings = "{}";
  // Agreement the method promises with the bssrdf reference on the conformance scene with quick_settings:
  // relative error of the mean radiance over the object's pixels.
  double reference_tolerance = 0.25;
  bool needs_texture_atlas = false;  // texture-space methods: objects get an atlas, blob surfaces are refused
};

// Every registered method (src/methods/method_list.h), the default first.
std::span<const MethodInfo* const> method_registry();
const MethodInfo* find_method(std::string_view name);
const MethodInfo& default_method();

}  // namespace lucent::methods
