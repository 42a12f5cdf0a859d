// shader_program.h: a linked GL program built from embedded shader files.
#pragma once
#include <string>

#include <epoxy/gl.h>

namespace lucent::gpu {

class ShaderProgram {
 public:
  ShaderProgram() = default;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;
  ShaderProgram(ShaderProgram&& other) noexcept : id_(other.id_) { other.id_ = 0; }
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ~ShaderProgram();

  // Each throws lucent::Error("shader <file>:<line>: <driver message>") when compiling or linking fails.
  static ShaderProgram compute(const std::string& path, const std::string& defines = "");
  static ShaderProgram graphics(const std::string& vertex, const std::string& geometry, const std::string& fragment,
                                const std::string& defines = "");  // geometry may be ""

  GLuint id() const { return id_; }

 private:
  explicit ShaderProgram(GLuint id) : id_(id) {}
  GLuint id_ = 0;
};

}  // namespace lucent::gpu
