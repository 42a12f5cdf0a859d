// image_compare.cpp: see image_compare.h.
#include "image_compare.h"

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include "gpu/shader_sources.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <vector>

#include "lucent/context.h"
#include "../test_paths.h"

namespace lucent::test {

ImageDifference compare(const ImageRGBA8& actual, const ImageRGBA8& expected) {
  ImageDifference d;
  if (actual.width != expected.width || actual.height != expected.height) {
    d.mean_abs = d.percentile_99 = 255.0;
    d.max_abs = 255;
    return d;
  }
  std::vector<int> per_pixel;
  double sum = 0.0, signed_sum = 0.0;
  for (std::size_t i = 0; i < actual.pixels.size(); i += 4) {
    int worst = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      int signed_diff = int(actual.pixels[i + c]) - int(expected.pixels[i + c]);
      int diff = std::abs(signed_diff);
      signed_sum += signed_diff;
      sum += diff;
      worst = std::max(worst, diff);
    }
    per_pixel.push_back(worst);
    d.max_abs = std::max(d.max_abs, worst);
  }
  d.mean_abs = sum / (3.0 * static_cast<double>(per_pixel.size()));
  d.mean_signed = signed_sum / (3.0 * static_cast<double>(per_pixel.size()));
  std::sort(per_pixel.begin(), per_pixel.end());
  d.percentile_99 = per_pixel[static_cast<std::size_t>(0.99 * static_cast<double>(per_pixel.size() - 1))];
  return d;
}

ImageRGBA8 difference_image(const ImageRGBA8& actual, const ImageRGBA8& expected) {
  ImageRGBA8 out = actual;
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      int diff = i < expected.pixels.size() ? std::abs(int(actual.pixels[i + c]) - int(expected.pixels[i + c])) : 255;
      out.pixels[i + c] = static_cast<std::uint8_t>(std::min(255, 8 * diff));
    }
    out.pixels[i + 3] = 255;
  }
  return out;
}

std::string output_path(const std::string& name) {
  std::filesystem::create_directories(LUCENT_TEST_OUT);
  return (std::filesystem::path(LUCENT_TEST_OUT) / name).string();
}

void ensure_gl_context() {
  static std::unique_ptr<GLContext> context = create_headless_context();
  context->make_current();
}


std::string embedded_without_includes(const std::string& path) {
  for (std::size_t i = 0; i < gpu::kEmbeddedFileCount; ++i) {
    if (path != gpu::kEmbeddedFiles[i].path) continue;
    std::string text(gpu::kEmbeddedFiles[i].text, gpu::kEmbeddedFiles[i].size), out;
    std::size_t begin = 0;
    while (begin < text.size()) {
      std::size_t end = text.find('\n', begin);
      if (end == std::string::npos) end = text.size();
      const std::string line = text.substr(begin, end - begin);
      if (line.rfind("#include", 0) != 0) out += line + "\n";
      begin = end + 1;
    }
    return out;
  }
  ADD_FAILURE() << path << " is not embedded";
  return "";
}


unsigned compile_compute_source(const std::string& source) {
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  std::string log(4096, '\0');
  glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  if (ok != GL_TRUE) {
    ADD_FAILURE() << log;
    glDeleteShader(shader);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  return program;
}

}  // namespace lucent::test
