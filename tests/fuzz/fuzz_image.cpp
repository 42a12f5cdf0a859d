// fuzz_image.cpp: libFuzzer target for image files. The first byte picks the reader (Radiance HDR, PNG, EXR),
// the rest is the file; a readable image then goes through the environment-map checks and, when small, the
// conversion to directional lights. A lucent::Error is the expected answer to bad input; any other exception, a
// crash, a hang or a leak is a bug.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "lucent/environment.h"
#include "lucent/error.h"
#include "lucent/image.h"

namespace {

lucent::ImageRGBA32F to_float(const lucent::ImageRGBA8& image) {
  lucent::ImageRGBA32F result{image.width, image.height, {}};
  result.pixels.assign(image.pixels.begin(), image.pixels.end());
  return result;
}

lucent::ImageRGBA32F read(const std::uint8_t* data, std::size_t size) {
  switch (data[0] % 3) {
    case 0: return lucent::read_hdr(lucent::fuzz::write_input(data + 1, size - 1, ".hdr"));
    case 1: return to_float(lucent::read_png(lucent::fuzz::write_input(data + 1, size - 1, ".png")));
    default: return lucent::read_exr(lucent::fuzz::write_input(data + 1, size - 1, ".exr"));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  try {
    const lucent::ImageRGBA32F image = read(data, size);
    const lucent::EnvironmentMap map = lucent::environment_map_from_image(image, "fuzz");
    if (map.width <= 256) lucent::environment_to_directional_lights(map, 1 + data[0] % 8);
  } catch (const lucent::Error&) {
  }
  return 0;
}
