// fuzz_vdb.cpp: libFuzzer target for OpenVDB files. The first byte picks the transform (object-bounds,
// vdb-world) and the grid name (density, or the empty name), the rest is the file, read by load_medium_vdb: the
// header check in this process, OpenVDB in its guarded child. A lucent::Error is the expected answer to bad input;
// any other exception, a crash, a hang or a leak in this process is a bug.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "lucent/error.h"
#include "lucent/medium_vdb.h"
#include "scene/import_guard.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lucent::vdb_read_limits().cpu_seconds = 4;
  lucent::vdb_read_limits().wall_seconds = 8;
  // Always in the child: libFuzzer's memory-watch thread would otherwise make the sanitizer build read in-process,
  // and the target would fuzz OpenVDB itself (its leaks and crashes on hostile files are what the child contains).
  lucent::vdb_read_limits().in_process_when_threaded_under_asan = false;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  lucent::VdbField field;
  field.file = lucent::fuzz::write_input(data + 1, size - 1, ".vdb");
  field.transform = data[0] % 2 ? lucent::VdbTransform::VdbWorld : lucent::VdbTransform::ObjectBounds;
  if (data[0] & 2) field.grid = "";
  try {
    lucent::load_medium_vdb(field);
  } catch (const lucent::Error&) {
  }
  return 0;
}
