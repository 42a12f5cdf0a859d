// shader_sources.h: shader text embedded in the binary, with #include resolved and file names kept so that a
// compiler message "3:42" can be reported as "radiosity_maps/integrate.comp:42".
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace lucent::gpu {

struct EmbeddedFile {
  const char* path;  // "bssrdf/fresnel.h", "methods/radiosity_maps/shaders/integrate.comp"
  const char* text;
  std::size_t size;
};
extern const EmbeddedFile kEmbeddedFiles[];
extern const std::size_t kEmbeddedFileCount;

struct ExpandedSource {
  std::string text;                 // "#version 450 core" + defines + expanded file
  std::vector<std::string> files;   // source-string number (as in #line) -> embedded path
  // Replaces every "N:L" / "N(L)" reference in a driver log with "file:L".
  std::string annotate_log(const std::string& log) const;
};

// Expands `path` and its includes (each file at most once). `defines` are extra "#define" lines.
// Throws lucent::Error naming the shader when a file is not embedded.
ExpandedSource expand_shader(const std::string& path, const std::string& defines = "");

}  // namespace lucent::gpu
