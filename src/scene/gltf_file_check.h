// gltf_file_check.h: what a glTF file must pass before any reader (tinygltf in-process, assimp in the guarded
// importer) allocates for it or opens what it names.
//
// The readers trust the file: a GLB whose header declares a 2 GB JSON chunk in 500 bytes makes them allocate 2 GB,
// a buffer URI naming a FIFO blocks the reader forever, a sparse file declares gigabytes it does not hold. And the
// glTF 2.0 specification lists what a loader must reject, which they accept: an extension in extensionsRequired
// that the loader does not implement, a negative byteOffset, an index past the end of its vertex attributes
// (assimp drops the triangle without a word).
#pragma once
#include <string>

namespace lucent {

// Throws lucent::Error("<path>: <JSON pointer>: <problem>") for:
// - a GLB whose header or chunk lengths exceed the file;
// - an entry of extensionsRequired that lucent does not read (kGltfReadExtensions);
// - a buffer or image URI naming something other than a regular file, a buffer file holding fewer bytes than its
//   byteLength, or a sparse one (far fewer bytes stored than its size);
// - a bufferView or accessor byteOffset that is not a non-negative whole number;
// - a primitive's index at or past its POSITION accessor's count.
// Does nothing for a file that is not glTF JSON or GLB (the reader names that problem).
void check_gltf_file(const std::string& path);

}  // namespace lucent
