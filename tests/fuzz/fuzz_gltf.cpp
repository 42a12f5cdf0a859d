// fuzz_gltf.cpp: libFuzzer target for glTF materials (tinygltf in lucent's own process, unlike the mesh importer).
// The first byte picks .gltf or .glb, the rest is the file; read_gltf_material (container, JSON, extensions, the
// base-colour texture's image) and its mapping to lucent's parameters must answer bad input with lucent::Error.
// Any other exception, a crash, a hang or a leak is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "lucent/error.h"
#include "lucent/warning.h"
#include "scene/gltf_material.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lucent::set_warning_handler([](const std::string&) {});  // the ignored-field lines of every input
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string path = lucent::fuzz::write_input(data + 1, size - 1, data[0] % 2 ? ".glb" : ".gltf");
  try {
    lucent::lucent_material(lucent::read_gltf_material(path));
  } catch (const lucent::Error&) {
  }
  return 0;
}
