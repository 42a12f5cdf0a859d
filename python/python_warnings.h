// python_warnings.h: lucent's warnings (lucent/warning.h) as Python warnings of category lucent.LucentWarning.
// The library may warn on any thread (a TBB worker, a render thread) without the GIL, so its handler only queues
// the message; the module's calls emit the queue on the calling thread, with the GIL, before they return.
#pragma once
#include <utility>

#include <pybind11/pybind11.h>

namespace lucent::python {

// Adds lucent.LucentWarning (a UserWarning) to the module and installs the queueing handler.
void bind_warnings(pybind11::module_& m);

// warnings.warn(message, LucentWarning) for each queued message, oldest first; the GIL held. Raises what
// warnings.warn raises (a warnings filter of "error" turns one into an exception).
void emit_warnings();

// Calls `f` and emits the warnings it queued, also when it throws (the exception is then the one raised).
template <class F>
auto emitting_warnings(F&& f) {
  try {
    auto result = std::forward<F>(f)();
    emit_warnings();
    return result;
  } catch (...) {
    try {
      emit_warnings();
    } catch (...) {  // the call's own exception says more than a warning turned into an error
    }
    throw;
  }
}

}  // namespace lucent::python
