// context.h: the OpenGL 4.5 core context lucent renders with: headless EGL or a GLFW window, behind one
// small interface. Rendering code never sees a window.
#pragma once
#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace lucent {

class GLContext {
 public:
  virtual ~GLContext() = default;
  // Makes the context current on the calling thread. A context is current on one thread at a time: another
  // thread takes it after release_current() on the thread that has it.
  virtual void make_current() = 0;
  // The calling thread lets go of the context (no context current on it afterwards).
  virtual void release_current() = 0;
  // "NVIDIA H100 ..., 4.5.0 NVIDIA 550" / "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6"
  virtual std::string description() const = 0;
};

// A context with no window: EGL on the surfaceless platform (Mesa, including llvmpipe), falling back to the
// EGL device platform (NVIDIA). Throws lucent::Error with one line when no display, no OpenGL 4.5 core
// context or a required limit is missing.
std::unique_ptr<GLContext> create_headless_context();
// The EGL devices a headless context can be created on (EGL_EXT_device_enumeration), in index order: each one's
// renderer, DRM node or "software rasterizer (Mesa)". One entry, the default display, where the driver cannot
// enumerate devices.
std::vector<std::string> headless_devices();
// A headless context on device `device` of headless_devices() (-1: the default, as above). Throws lucent::Error
// naming the number of devices for an index beyond them.
std::unique_ptr<GLContext> create_headless_context(int device);

class WindowContext : public GLContext {
 public:
  virtual GLFWwindow* window() = 0;
  virtual void swap_buffers() = 0;
};
// A GLFW window with an OpenGL 4.5 core context. Throws lucent::Error when GLFW or the context fails.
std::unique_ptr<WindowContext> create_window_context(int width, int height, const std::string& title);

}  // namespace lucent
