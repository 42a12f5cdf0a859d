// command_compare.cpp: `lucent compare A B`: error of image A against reference B (EXR or PNG), on linear and on
// tone-mapped values, with a heat-map difference image. B's standard error is read from B.stderr.exr if present.
//
// A PNG is display-referred (lucent render's PNG is ACES tone-mapped, then sRGB encoded): its "linear" values are
// the sRGB curve decoded, display light in [0, 1], not radiance; its "display" values are its codes / 255, compared
// with an EXR's tone-mapped values. Radiance errors need two EXRs.
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "option_checks.h"
#include "image/image_error_json.h"
#include "image/image_metrics.h"
#include "lucent/error.h"
#include "lucent/output_file.h"
#include "params/argument_ranges.h"
#include "reference/reference_files.h"

namespace lucent::cli {
namespace {

struct CompareOptions {
  std::string a, b, diff;
  float exposure = 0.0f;
  double scale = 0.0;
  bool json = false;
};

constexpr const char* kPngNote =
    "a PNG is tone-mapped: its linear values are the sRGB curve decoded (display light in [0, 1]), not radiance; "
    "compare two EXRs for radiance errors";

// An input's values for both rows of the comparison: an EXR's radiance and its tone-mapped values, or a PNG's
// decoded display light and its codes.
struct CompareImage {
  ImageRGBA32F linear, display;
  bool display_referred = false;
};

CompareImage read_compare_image(const std::string& path, float exposure) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".png") {
    const ImageRGBA8 png = read_png(path);
    return {from_srgb8(png, true), from_srgb8(png, false), true};
  }
  if (extension != ".exr") throw Error(fmt::format("{}: compare reads .exr and .png images", path));
  ImageRGBA32F exr = read_exr(path);
  ImageRGBA32F display = tonemapped(exr, exposure);
  return {std::move(exr), std::move(display), false};
}

void run(const CompareOptions& o) {
  std::string se_path = reference::reference_files(o.b).standard_error;
  const std::vector<OutputPath> outputs = {{o.diff, "--diff", {".png"}}};
  check_outputs(outputs, {o.a, o.b, se_path});
  const OutputLock lock(outputs);
  const CompareImage a_in = read_compare_image(o.a, o.exposure), b_in = read_compare_image(o.b, o.exposure);
  const ImageRGBA32F &a = a_in.linear, &b = b_in.linear;
  if (a.width != b.width || a.height != b.height)
    throw Error(fmt::format("{} is {}x{} but {} is {}x{}; compare needs images of one size", o.a, a.width, a.height,
                            o.b, b.width, b.height));
  std::optional<ImageRGBA32F> se;
  // A PNG reference's values are display light: a standard error of radiance does not apply to them.
  if (!b_in.display_referred && std::filesystem::exists(se_path)) se = read_exr(se_path);
  if (se && (se->width != b.width || se->height != b.height))
    throw Error(fmt::format("{} is {}x{} but its reference {} is {}x{}", se_path, se->width, se->height, o.b, b.width,
                            b.height));
  ImageError linear = image_error(a, b, se ? &*se : nullptr, {o.a, o.b, se_path});
  ImageError display = display_values_error(a_in.display, b_in.display);
  const bool png = a_in.display_referred || b_in.display_referred;
  if (!o.diff.empty()) {
    double scale = o.scale > 0.0 ? o.scale : std::max(1e-6, 4.0 * linear.rmse_rgb);
    write_png(o.diff, heat_map(a, b, scale));
  }
  if (o.json) {
    nlohmann::json j{{"a", o.a}, {"b", o.b}, {"linear", to_json(linear)}, {"display", to_json(display)}};
    if (png) j["note"] = kPngNote;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("{} vs {} ({}x{})\n", o.a, o.b, a.width, a.height);
  if (png) fmt::print("  note: {}\n", kPngNote);
  for (auto [name, e] : {std::pair{"linear", linear}, std::pair{"display", display}})
    fmt::print("  {:<8} RMSE r/g/b {:.5f} {:.5f} {:.5f}  sqrt(dr2+dg2+db2) {:.5f}  relMSE {:.5f}  mean error "
               "{:+.5f} +- {:.5f}  PSNR {}\n",
               name, e.rmse[0], e.rmse[1], e.rmse[2], e.rmse_rgb, e.relative_mse, e.mean_error, e.mean_error_se,
               psnr_text(e.psnr_db));
  if (se) fmt::print("  reference noise (RMS standard error) {:.5f}\n", linear.reference_noise_rms);
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "error of image A against reference B (EXR or PNG; a PNG is tone-mapped: its errors are in display "
                 "values, not radiance)");
  cmd->add_option("a", o->a, "image to measure (EXR, or PNG decoded from sRGB)")->required();
  cmd->add_option("b", o->b, "reference (EXR or PNG); B.stderr.exr is used when present")->required();
  cmd->add_option("--diff", o->diff, "write a heat map of sqrt(dr^2+dg^2+db^2) (PNG)");
  cmd->add_option("--diff-scale", o->scale, "radiance difference shown as white (default 4 x RMSE)")
      ->check(number_in(1e-30, 1e30));
  cmd->add_option("--exposure", o->exposure, "exposure [stops] for the tone-mapped comparison")
      ->check(number_in(argument_ranges::kExposureStops))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON");
  cmd->callback([o] { run(*o); });
}

void add_tonemap_command(CLI::App& app) {
  auto input = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto exposure = std::make_shared<float>(0.0f);
  CLI::App* cmd = app.add_subcommand("tonemap", "tone-map an EXR to PNG (ACES, sRGB), as lucent render does");
  cmd->add_option("input", *input, "linear EXR")->required();
  cmd->add_option("-o,--output", *output, "PNG")->required();
  cmd->add_option("--exposure", *exposure, "exposure [stops]")
      ->check(number_in(argument_ranges::kExposureStops))
      ->capture_default_str();
  cmd->callback([input, output, exposure] {
    const std::vector<OutputPath> outputs = {{*output, "--output", {".png"}}};
    check_outputs(outputs, {*input});
    const OutputLock lock(outputs);
    const ImageRGBA32F image = read_exr(*input);
    check_displayable(image, *input);
    write_png(*output, to_display(image, *exposure));
  });
}

}  // namespace lucent::cli
