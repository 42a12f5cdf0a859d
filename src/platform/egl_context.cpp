// egl_context.cpp: headless OpenGL 4.5 core through EGL: the surfaceless platform (Mesa, llvmpipe included)
// first, then the device platform (NVIDIA's driver), with no window system and no pbuffer.
#include <cstdlib>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include "lucent/context.h"
#include "lucent/error.h"
#include "platform/gl_capabilities.h"

namespace lucent {
namespace {

EGLDisplay open_display() {
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
  }
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (eglQueryDevicesEXT(8, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
      }
    }
  }
  throw Error(
      "no OpenGL context: EGL found no surfaceless or device display (install Mesa's libegl-mesa0 and "
      "libgl1-mesa-dri, or a GPU driver with EGL)");
}

class EglContext final : public GLContext {
 public:
  EglContext() {
    display_ = open_display();
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attributes, &config, 1, &count) || count == 0) {
      const EGLint pbuffer_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                           EGL_NONE};
      if (!eglChooseConfig(display_, pbuffer_attributes, &config, 1, &count) || count == 0)
        fail("EGL has no OpenGL-capable config");
    }
    std::vector<EGLint> attributes = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
#if defined(LUCENT_GL_DEBUG)
    attributes.insert(attributes.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
#endif
    attributes.push_back(EGL_NONE);
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attributes.data());
    if (context_ == EGL_NO_CONTEXT)
      fail(fmt::format("the driver cannot create an OpenGL 4.5 core context (EGL error 0x{:x})", eglGetError()));
    make_current();
    caps_ = platform::check_capabilities();
  }

  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }

  void make_current() override {
    if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return;
    const EGLint error = eglGetError();
    if (error == EGL_BAD_ACCESS)  // EGL: a context is current on one thread at a time
      throw Error("no OpenGL context: the headless context is current on another thread (release_current() there "
                  "first)");
    throw Error(fmt::format("no OpenGL context: eglMakeCurrent without a surface failed (EGL error 0x{:x})", error));
  }

  void release_current() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

  std::string description() const override { return caps_.renderer + ", OpenGL " + caps_.version; }

 private:
  [[noreturn]] void fail(const std::string& what) {
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
    throw Error("no OpenGL context: " + what);
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  platform::GLCapabilities caps_;
};

}  // namespace

std::unique_ptr<GLContext> create_headless_context() { return std::make_unique<EglContext>(); }

}  // namespace lucent
