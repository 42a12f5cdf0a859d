// gl_context.h: the module's one headless OpenGL context, on a chosen EGL device, created by the first render
// after lucent.Context(device=...) or lucent.release(), and current on one thread at a time.
#pragma once
#include <mutex>
#include <vector>

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

  // Counts the contexts the module has created: objects made in this one belong to this generation only.
  unsigned generation() const { return generation_; }

 private:
  std::unique_lock<std::mutex> lock_;
  GLContext* context_;
  unsigned generation_ = 0;
};

// What keeps OpenGL objects in the module's context across calls (a lucent.Renderer): before the context is
// destroyed (lucent.release(), a new lucent.Context) each resident drops its objects, with the context current on
// the releasing thread. Register and unregister while holding a CurrentContext.
class ContextResident {
 public:
  virtual void drop_gl_objects() = 0;

 protected:
  ~ContextResident() = default;
};
void add_resident(ContextResident* resident);
void remove_resident(ContextResident* resident);
// The same without holding a CurrentContext (takes the module's mutex itself): for a resident whose context could
// not be made current.
void forget_resident(ContextResident* resident);
// The generation of the module's context if one exists now, else 0; never creates one.
unsigned existing_context_generation();

}  // namespace lucent::python
