// import_guard.h: runs a file reader (the mesh importer, the OpenVDB reader) in a child process, so that a crash,
// a runaway loop or a runaway allocation inside it becomes a lucent::Error instead of taking the program down.
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
  // Sanitizer builds only: read in this process instead when other threads run (read_in_child).
  bool in_process_when_threaded_under_asan = false;
};

// Process-wide limits of load_mesh's importer and load_medium_vdb's reader; the fuzz targets lower them.
ImportLimits& mesh_import_limits();
ImportLimits& vdb_read_limits();

// The names a guarded reader's messages use: "<path>: <failure>: <reader> crashed (signal 11, ...)".
struct GuardedReader {
  std::string failure = "cannot read mesh";
  std::string reader = "the importer";
};

// Calls `read` in a forked child and returns the bytes it returned, read back through a pipe and shared memory.
// A lucent::Error thrown by `read` is rethrown here with the same message; another std::exception as
// "<path>: <failure>: <reader> failed: <what>", std::bad_alloc as "... ran out of memory (limit N MiB)".
// When the child dies (signal, CPU or memory limit, sanitizer report) or does not finish within the wall time,
// throws lucent::Error("<path>: <failure>: <reader> crashed (signal 11, Segmentation fault)") or similar.
std::string read_in_child(const std::string& path, const GuardedReader& names,
                          const std::function<std::string()>& read, const ImportLimits& limits);

// read_in_child for the mesh importer: the mesh `import` produced (positions, normals, indices, texture
// coordinates when it has them), as the child built it: the caller validates it. Messages as read_in_child's,
// "<path>: cannot read mesh: the importer crashed (signal 11, Segmentation fault)".
TriangleMesh import_in_child(const std::string& path, const std::function<TriangleMesh()>& import,
                             const ImportLimits& limits);

}  // namespace lucent
