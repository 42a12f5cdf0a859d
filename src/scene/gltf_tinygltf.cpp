// gltf_tinygltf.cpp: tinygltf's implementation (Debian's libtinygltf-dev ships the header; the library is compiled
// here, once, so lucent builds wherever tiny_gltf.h and nlohmann/json.hpp are installed).
//
// Without stb_image: tinygltf keeps images encoded (gltf_reader.cpp's loader callback stores the bytes) and lucent
// decodes the ones it uses with its own image reader and its size checks (lucent/image.h, decode_image). Without
// stb_image_write: lucent writes no images into glTF files.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#define TINYGLTF_IMPLEMENTATION
#include "scene/gltf_tinygltf.h"
#pragma GCC diagnostic pop
