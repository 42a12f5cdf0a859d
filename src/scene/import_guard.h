// import_guard.h: runs a mesh importer in a child process, so that a crash, a runaway loop or a runaway
// allocation inside it becomes a lucent::Error instead of taking the program down.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "lucent/mesh.h"

namespace lucent {

struct ImportLimits {
  int cpu_seconds = 300;   // RLIMIT_CPU of the child: SIGXCPU past it
  int wall_seconds = 900;  // the parent kills the child when no result has come by then (e.g. a deadlock)
  // Address space the child may add to what it inherits (RLIMIT_AS); 0 = unlimited. Not applied under
  // AddressSanitizer, whose shadow memory reserves terabytes of address space.
  std::uint64_t memory_bytes = 0;
};

// Process-wide limits of load_mesh's importer; the fuzz targets lower them.
ImportLimits& mesh_import_limits();

// Calls `import` in a forked child and returns the mesh it produced, read back through a pipe and shared memory
// (positions, normals, indices, texture coordinates when it has them). A lucent::Error or std::exception thrown by `import` is rethrown here with the same message.
// When the child dies (signal, CPU or memory limit, sanitizer report) or does not finish within the wall time,
// throws lucent::Error("<path>: cannot read mesh: the importer crashed (signal 11, Segmentation fault)") or
// similar. Returns the mesh as the child built it: the caller validates it.
TriangleMesh import_in_child(const std::string& path, const std::function<TriangleMesh()>& import,
                             const ImportLimits& limits);

}  // namespace lucent
