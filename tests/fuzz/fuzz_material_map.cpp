// fuzz_material_map.cpp: libFuzzer target for textured materials. The first byte picks the map's image type (PNG,
// EXR, Radiance HDR) and key (albedo_map, mfp_map), the rest is the image file; a scene of one sphere whose
// material names that map is parsed, which reads the image and inverts it texel by texel. A lucent::Error is the
// expected answer to bad input; any other exception, a crash, a hang or a leak is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "lucent/error.h"
#include "lucent/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {".png", ".exr", ".hdr"};
  const std::string extension = kExtensions[data[0] % 3];
  const std::string key = data[0] & 4 ? "mfp_map" : "albedo_map";
  lucent::fuzz::write_input(data + 1, size - 1, extension);
  const std::string scene = R"({"lights": [{"direction": [0, -1, 0]}], "objects": [{"shape": "sphere",
    "material": {"mfp_mm": 2.0, ")" + key + R"(": "input)" + extension + R"("}}],
    "method": {"name": "radiosity-maps"}})";
  try {
    lucent::parse_scene(scene, "fuzz.json", lucent::fuzz::temp_dir().string());
  } catch (const lucent::Error&) {
  }
  return 0;
}
