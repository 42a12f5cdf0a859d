// medium_vdb_reader.h: the OpenVDB reader behind load_medium_vdb (lucent/medium_vdb.h), in library lucent_vdb.
// load_medium_vdb checks the file's layout (media/vdb_header_check.h) and runs this reader in a guarded child
// process (scene/import_guard.h); nothing else calls it.
#pragma once
#include "lucent/medium_vdb.h"

namespace lucent {

// The grid of `field` resampled as lucent/medium_vdb.h describes, read in this process. Throws lucent::Error
// naming the file; OpenVDB may allocate what the file declares before it finds a problem.
VdbVolume read_medium_vdb(const VdbField& field);

}  // namespace lucent
