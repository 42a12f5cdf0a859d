// shader_program.cpp: compiles and links embedded shaders; driver logs are reported with file names.
#include "gpu/shader_program.h"

#include <vector>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/shader_sources.h"
#include "lucent/error.h"

namespace lucent::gpu {
namespace {

std::string first_error_line(const std::string& log) {
  auto pos = log.find("error");
  if (pos == std::string::npos) pos = 0;
  auto line_start = log.rfind('\n', pos);
  line_start = line_start == std::string::npos ? 0 : line_start + 1;
  auto line_end = log.find('\n', pos);
  return log.substr(line_start, line_end == std::string::npos ? std::string::npos : line_end - line_start);
}

GLuint compile_stage(GLenum stage, const std::string& path, const std::string& defines) {
  ExpandedSource source = expand_shader(path, defines);
  GLuint shader = glCreateShader(stage);
  const char* text = source.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw Error(fmt::format("shader {}: compile error: {}", path, first_error_line(source.annotate_log(log))));
  }
  return shader;
}

GLuint link(const std::vector<GLuint>& shaders, const std::string& name) {
  GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw Error(fmt::format("shader {}: link error: {}", name, first_error_line(log)));
  }
  label_object(GL_PROGRAM, program, name);
  return program;
}

}  // namespace

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteProgram(id_);
    id_ = other.id_;
    other.id_ = 0;
  }
  return *this;
}

ShaderProgram::~ShaderProgram() {
  if (id_) glDeleteProgram(id_);
}

ShaderProgram ShaderProgram::compute(const std::string& path, const std::string& defines) {
  return ShaderProgram(link({compile_stage(GL_COMPUTE_SHADER, path, defines)}, path));
}

ShaderProgram ShaderProgram::graphics(const std::string& vertex, const std::string& geometry,
                                      const std::string& fragment, const std::string& defines) {
  std::vector<GLuint> stages;
  stages.push_back(compile_stage(GL_VERTEX_SHADER, vertex, defines));
  if (!geometry.empty()) stages.push_back(compile_stage(GL_GEOMETRY_SHADER, geometry, defines));
  stages.push_back(compile_stage(GL_FRAGMENT_SHADER, fragment, defines));
  return ShaderProgram(link(stages, vertex + "+" + fragment));
}

}  // namespace lucent::gpu
