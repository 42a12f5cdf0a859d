// gl_context.cpp: lucent.devices, lucent.Context and lucent.release: which EGL device the module renders on, and
// letting go of its context.
#include "gl_context.h"

#include <memory>
#include <optional>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.h"

namespace lucent::python {
namespace {

struct ModuleContext {
  std::mutex mutex;                   // held by a render for as long as the context is current on its thread
  std::unique_ptr<GLContext> context;  // none before the first render and after release()
  int device = -1;                     // the EGL device of the next context (-1: the default display)
  unsigned generation = 0;             // counts the contexts created, so that a Context closes only its own
  std::vector<ContextResident*> residents;  // objects kept in the context between calls
};

// Never destroyed: tearing EGL down while the interpreter exits (after the driver's own atexit handlers may have
// run) is not safe; a context still open then ends with the process. release() destroys one explicitly.
ModuleContext& module_context() {
  static auto* state = new ModuleContext;
  return *state;
}

// Creates the context on `state.device`; the caller holds state.mutex.
void open(ModuleContext& state) {
  state.context = create_headless_context(state.device);
  state.context->release_current();  // made current by its constructor on this thread; renders take it
  ++state.generation;
}

// Destroys the context; the caller holds state.mutex. Residents drop their objects first, with it current here.
void close(ModuleContext& state) {
  if (state.context && !state.residents.empty()) {
    state.context->make_current();
    for (ContextResident* resident : state.residents) resident->drop_gl_objects();
    state.context->release_current();
  }
  state.residents.clear();
  state.context.reset();
}

// lucent.Context: opens the module's context on a device now (a bad device raises here, not at the render).
class PyContext {
 public:
  explicit PyContext(std::optional<int> device) {
    const int count = static_cast<int>(headless_devices().size());
    if (device && (*device < 0 || *device >= count))
      throw py::value_error(fmt::format("device {} does not exist; there {} {} EGL device{} (0 to {}, see "
                                        "lucent.devices())",
                                        *device, count == 1 ? "is" : "are", count, count == 1 ? "" : "s", count - 1));
    ModuleContext& state = module_context();
    const py::gil_scoped_release unlocked;  // a render on another thread may hold the context
    const std::lock_guard<std::mutex> lock(state.mutex);
    close(state);
    state.device = device.value_or(-1);
    open(state);
    generation_ = state.generation;
    description_ = state.context->description();
    device_ = state.device;
  }

  // Destroys the context if it is still this one; the next render creates a fresh one on the same device.
  void close_context() {
    ModuleContext& state = module_context();
    const py::gil_scoped_release unlocked;
    const std::lock_guard<std::mutex> lock(state.mutex);
    if (state.context && state.generation == generation_) close(state);
    closed_ = true;
  }

  bool closed() const { return closed_ || module_context().generation != generation_ || !module_context().context; }
  std::optional<int> device() const { return device_ < 0 ? std::nullopt : std::optional<int>(device_); }
  const std::string& description() const { return description_; }

 private:
  unsigned generation_ = 0;
  int device_ = -1;
  std::string description_;
  bool closed_ = false;
};

void release() {
  ModuleContext& state = module_context();
  const py::gil_scoped_release unlocked;
  const std::lock_guard<std::mutex> lock(state.mutex);
  close(state);
}

}  // namespace

CurrentContext::CurrentContext() : lock_(module_context().mutex) {
  ModuleContext& state = module_context();
  if (!state.context) open(state);
  context_ = state.context.get();
  generation_ = state.generation;
  context_->make_current();
}

void add_resident(ContextResident* resident) { module_context().residents.push_back(resident); }

void remove_resident(ContextResident* resident) {
  std::vector<ContextResident*>& residents = module_context().residents;
  std::erase(residents, resident);
}

void forget_resident(ContextResident* resident) {
  const std::lock_guard<std::mutex> lock(module_context().mutex);
  remove_resident(resident);
}

unsigned existing_context_generation() {
  ModuleContext& state = module_context();
  const std::lock_guard<std::mutex> lock(state.mutex);
  return state.context ? state.generation : 0u;
}

CurrentContext::~CurrentContext() { context_->release_current(); }

void bind_context(py::module_& m) {
  m.def("devices", &headless_devices,
        "The EGL devices lucent can render on (EGL_EXT_device_enumeration), in the order lucent.Context(device=N) "
        "numbers them: each one's renderer, DRM node or \"software rasterizer (Mesa)\".");
  py::class_<PyContext>(m, "Context",
                        "The module's headless OpenGL context, opened now on EGL device `device` (an index into "
                        "lucent.devices(); None: the default display, Mesa's surfaceless platform first). It "
                        "replaces the context renders used so far. close() (or leaving a `with` block) destroys "
                        "it; the next render then creates a fresh one on the same device.")
      .def(py::init<std::optional<int>>(), py::arg("device") = py::none())
      .def("close", &PyContext::close_context, "Destroys the context (when it is still the module's).")
      .def_property_readonly("closed", &PyContext::closed)
      .def_property_readonly("device", &PyContext::device)
      .def_property_readonly("description", &PyContext::description, "renderer and OpenGL version")
      .def("__enter__", [](PyContext& c) -> PyContext& { return c; }, py::return_value_policy::reference)
      .def("__exit__", [](PyContext& c, const py::args&) { c.close_context(); })
      .def("__repr__", [](const PyContext& c) {
        return fmt::format("<lucent.Context device {} ({}){}>", c.device() ? std::to_string(*c.device()) : "default",
                           c.description(), c.closed() ? ", closed" : "");
      });
  m.def("release", &release,
        "Destroys the module's OpenGL context (and the GPU memory it holds), if any; the next render creates a "
        "fresh one on the device last chosen.");
}

}  // namespace lucent::python
