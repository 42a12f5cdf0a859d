// glfw_context.cpp: a window with an OpenGL 4.5 core context, for the viewer and applications that want one.
#include <epoxy/gl.h>
// epoxy must come before GLFW so that GLFW does not pull in the system GL header.
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include "lucent/context.h"
#include "lucent/error.h"
#include "platform/gl_capabilities.h"

namespace lucent {
namespace {

class GlfwContext final : public WindowContext {
 public:
  GlfwContext(int width, int height, const std::string& title) {
    if (!glfwInit()) throw Error("no OpenGL context: GLFW cannot initialise (is a display available?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#if defined(LUCENT_GL_DEBUG)
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw Error("no OpenGL context: GLFW cannot create a window with OpenGL 4.5 core");
    }
    make_current();
    caps_ = platform::check_capabilities();
  }
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  void make_current() override { glfwMakeContextCurrent(window_); }
  void release_current() override { glfwMakeContextCurrent(nullptr); }
  std::string description() const override { return caps_.renderer + ", OpenGL " + caps_.version; }
  GLFWwindow* window() override { return window_; }
  void swap_buffers() override { glfwSwapBuffers(window_); }

 private:
  GLFWwindow* window_ = nullptr;
  platform::GLCapabilities caps_;
};

}  // namespace

std::unique_ptr<WindowContext> create_window_context(int width, int height, const std::string& title) {
  return std::make_unique<GlfwContext>(width, height, title);
}

}  // namespace lucent
