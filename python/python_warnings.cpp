// python_warnings.cpp: see python_warnings.h.
#include "python_warnings.h"

#include <deque>
#include <mutex>
#include <string>

#include "bindings.h"
#include "lucent/warning.h"

namespace lucent::python {
namespace {

std::mutex queue_mutex;
std::deque<std::string> queue;     // warnings not yet emitted
PyObject* warning_type = nullptr;  // lucent.LucentWarning, owned by the module (kept alive for the process)

void enqueue(const std::string& message) {
  const std::lock_guard<std::mutex> lock(queue_mutex);
  queue.push_back(message);
}

bool pop(std::string& message) {
  const std::lock_guard<std::mutex> lock(queue_mutex);
  if (queue.empty()) return false;
  message = std::move(queue.front());
  queue.pop_front();
  return true;
}

}  // namespace

void emit_warnings() {
  std::string message;
  while (pop(message))
    if (PyErr_WarnEx(warning_type, message.c_str(), 1) != 0) throw py::error_already_set();
}

void bind_warnings(py::module_& m) {
  warning_type = PyErr_NewExceptionWithDoc(
      "lucent.LucentWarning",
      "Input lucent accepts but that will not render what was probably meant (a material far outside its model's "
      "validity, a translucent object no light reaches, ...).",
      PyExc_UserWarning, nullptr);
  if (!warning_type) throw py::error_already_set();
  m.add_object("LucentWarning", py::reinterpret_borrow<py::object>(warning_type));
  set_warning_handler(enqueue);  // for the life of the process: it holds no Python object
}

}  // namespace lucent::python
