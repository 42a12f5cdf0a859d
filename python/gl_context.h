// gl_context.h: the module's one headless OpenGL context, on a chosen EGL device, created by the first render
// after lucent.Context(device=...) or lucent.release(), and current on one thread at a time.
#pragma once
#include <mutex>

#include "lucent/context.h"

namespace lucent::python {

// Holds the module's context current on the calling thread (creating it first when there is none), and every
// other render out, for as long as it lives. Throws lucent::Error when the context cannot be created.
class CurrentContext {
 public:
  CurrentContext();
  ~CurrentContext();
  CurrentContext(const CurrentContext&) = delete;
  CurrentContext& operator=(const CurrentContext&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;
  GLContext* context_;
};

}  // namespace lucent::python
