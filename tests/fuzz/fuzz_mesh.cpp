// fuzz_mesh.cpp: libFuzzer target for mesh files. The first byte picks the extension (the importer chooses its
// parser by it, and by content), the rest is the file; load_mesh's result must pass validate_mesh. A
// lucent::Error is the expected answer to bad input; any other exception, a crash, a hang or a leak is a bug.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "lucent/error.h"
#include "lucent/mesh.h"
#include "scene/import_guard.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Below libFuzzer's -timeout, so that a runaway importer is an error here rather than a reported hang.
  lucent::mesh_import_limits().cpu_seconds = 4;
  lucent::mesh_import_limits().wall_seconds = 8;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const char* const kExtensions[] = {".ply", ".obj", ".stl", ".off", ".gltf", ".glb"};
  if (size < 1) return 0;
  const std::string path = lucent::fuzz::write_input(data + 1, size - 1, kExtensions[data[0] % 6]);
  try {
    lucent::validate_mesh(lucent::load_mesh(path), path);
  } catch (const lucent::Error&) {
  }
  return 0;
}
