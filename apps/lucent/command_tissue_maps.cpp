// command_tissue_maps.cpp: `lucent tissue-maps -o FILE`: the procedural tissue layer maps (media/tissue_maps.h) as a
// PNG or EXR file: channel j the thickness of layer j as a fraction of the stack's depth. Edit it and hand it back to
// layered-stm as `maps`, or build a volpath density field from it (scripts/make_tissue_volume.py).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "commands.h"
#include "lucent/lucent.h"
#include "media/tissue_maps.h"
#include "option_checks.h"

namespace lucent::cli {
namespace {

struct TissueMapsOptions {
  std::string output = "out/tissue_maps.png";
  int size = 512;
};

void run(const TissueMapsOptions& o) {
  const std::string ext = lowercase_extension(o.output);
  const std::vector<OutputPath> outputs = {{o.output, "--output", {".png", ".exr"}}};
  check_outputs(outputs, {});
  const OutputLock lock(outputs);
  const ImageRGBA32F maps = media::tissue_layer_maps(o.size);
  if (ext == ".exr") {
    write_exr(o.output, maps);
  } else {
    // Linear 8-bit channels (layered-stm reads a PNG as value / 255).
    ImageRGBA8 bytes{maps.width, maps.height, std::vector<std::uint8_t>(maps.pixels.size())};
    for (std::size_t i = 0; i < maps.pixels.size(); ++i)
      bytes.pixels[i] = static_cast<std::uint8_t>(std::lround(std::clamp(maps.pixels[i], 0.0f, 1.0f) * 255.0f));
    write_png(o.output, bytes);
  }
  fmt::print("tissue layer maps {}x{} -> {}\n", o.size, o.size, o.output);
}

}  // namespace

void add_tissue_maps_command(CLI::App& app) {
  auto o = std::make_shared<TissueMapsOptions>();
  CLI::App* cmd = app.add_subcommand("tissue-maps", "write the procedural tissue layer maps (layered-stm's maps) as PNG or EXR");
  cmd->add_option("-o,--output", o->output, "output file (.png: linear 8-bit, .exr: float)")->capture_default_str();
  cmd->add_option("--size", o->size, "width and height [texels]")->check(whole_number_in(16, 4096))->capture_default_str();
  cmd->callback([o] { run(*o); });
}

}  // namespace lucent::cli
