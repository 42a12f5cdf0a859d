// egl_context.cpp: headless OpenGL 4.5 core through EGL: the surfaceless platform (Mesa, llvmpipe included)
// first, then the device platform (NVIDIA's driver), with no window system and no pbuffer; or a chosen EGL device
// (EGL_EXT_device_enumeration, EGL_EXT_platform_device).
#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include "lucent/context.h"
#include "lucent/error.h"
#include "platform/gl_capabilities.h"

namespace lucent {
namespace {

constexpr EGLint kMaxDevices = 64;
constexpr EGLint kEglRendererExt = 0x335F;  // EGL_RENDERER_EXT (EGL_EXT_device_query_name; newer than epoxy here)

// The EGL devices (EGL_EXT_device_enumeration); none where the driver cannot enumerate them.
std::vector<EGLDeviceEXT> egl_devices() {
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
      !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base"))
    return {};
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(kMaxDevices));
  EGLint count = 0;
  if (!eglQueryDevicesEXT(kMaxDevices, devices.data(), &count) || count < 0) return {};
  devices.resize(static_cast<std::size_t>(count));
  return devices;
}

EGLDisplay initialized(EGLDisplay display) {
  return display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr) ? display : EGL_NO_DISPLAY;
}

EGLDisplay device_display(EGLDeviceEXT device) {
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) return EGL_NO_DISPLAY;
  return initialized(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr));
}

// The default display: the surfaceless platform (Mesa, llvmpipe included) first, then the first EGL device that
// opens (NVIDIA's driver).
EGLDisplay open_default_display() {
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
    if (EGLDisplay display = initialized(
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
        display != EGL_NO_DISPLAY)
      return display;
  for (EGLDeviceEXT device : egl_devices())
    if (EGLDisplay display = device_display(device); display != EGL_NO_DISPLAY) return display;
  throw Error(
      "no OpenGL context: EGL found no surfaceless or device display (install Mesa's libegl-mesa0 and "
      "libgl1-mesa-dri, or a GPU driver with EGL)");
}

// Device `index` of headless_devices(); -1 the default display.
EGLDisplay open_display(int index) {
  if (index < 0) return open_default_display();
  const std::vector<EGLDeviceEXT> devices = egl_devices();
  const int count = std::max<int>(1, static_cast<int>(devices.size()));
  if (index >= count)
    throw Error(fmt::format("no OpenGL context: EGL device {} does not exist; there {} {} (0 to {})", index,
                            count == 1 ? "is" : "are", count, count - 1));
  if (devices.empty()) return open_default_display();  // no enumeration: device 0 is the default display
  const EGLDisplay display = device_display(devices[static_cast<std::size_t>(index)]);
  if (display == EGL_NO_DISPLAY)
    throw Error(fmt::format("no OpenGL context: EGL device {} ({}) has no display (EGL error 0x{:x})", index,
                            headless_devices()[static_cast<std::size_t>(index)], eglGetError()));
  return display;
}

// What a device is: its renderer (EGL_EXT_device_query_name), else its DRM node, else Mesa's software renderer.
std::string device_description(EGLDeviceEXT device, std::size_t index) {
  const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
  const std::string ext = extensions ? extensions : "";
  if (ext.find("EGL_EXT_device_query_name") != std::string::npos)
    if (const char* name = eglQueryDeviceStringEXT(device, kEglRendererExt)) return name;
  if (ext.find("EGL_EXT_device_drm") != std::string::npos)
    if (const char* file = eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT)) return file;
  if (ext.find("EGL_MESA_device_software") != std::string::npos) return "software rasterizer (Mesa)";
  return fmt::format("EGL device {}", index);
}

class EglContext final : public GLContext {
 public:
  explicit EglContext(int device) {
    display_ = open_display(device);
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

std::vector<std::string> headless_devices() {
  const std::vector<EGLDeviceEXT> devices = egl_devices();
  if (devices.empty()) return {"the default EGL display"};
  std::vector<std::string> out;
  for (std::size_t i = 0; i < devices.size(); ++i) out.push_back(device_description(devices[i], i));
  return out;
}

std::unique_ptr<GLContext> create_headless_context(int device) { return std::make_unique<EglContext>(device); }

std::unique_ptr<GLContext> create_headless_context() { return create_headless_context(-1); }

}  // namespace lucent
