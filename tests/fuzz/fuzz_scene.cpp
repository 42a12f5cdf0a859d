// fuzz_scene.cpp: libFuzzer target for scene files: the bytes are the JSON text, meshes and environment maps
// resolve against tests/fuzz/scene_files/ (LUCENT_FUZZ_BASE_DIR). A lucent::Error is the expected answer to bad
// input; any other exception, a crash, a hang or a leak is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "lucent/error.h"
#include "lucent/scene.h"
#include "scene/import_guard.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lucent::mesh_import_limits().cpu_seconds = 4;
  lucent::mesh_import_limits().wall_seconds = 8;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    lucent::parse_scene(text, "fuzz.json", LUCENT_FUZZ_BASE_DIR);
  } catch (const lucent::Error&) {
  }
  return 0;
}
