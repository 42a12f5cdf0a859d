// bindings.h: the parts of the `lucent` Python module (one file each) and what they share.
#pragma once
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace lucent::python {

namespace py = pybind11;

void bind_errors(py::module_& m);     // lucent.Error
void bind_context(py::module_& m);    // devices, Context, release
void bind_tonemap(py::module_& m);    // tonemap
void bind_images(py::module_& m);     // read_exr, write_exr, write_png
void bind_scene(py::module_& m);      // Scene, load_scene
void bind_render(py::module_& m);     // render
void bind_renderer(py::module_& m);   // Renderer
void bind_reference(py::module_& m);  // reference
void bind_compare(py::module_& m);    // compare
void bind_bssrdf(py::module_& m);     // bssrdf, bssrdf_total
void bind_methods(py::module_& m);    // methods
void bind_materials(py::module_& m);  // materials

// A JSON value as Python objects (dict, list, float, int, str, bool, None), through Python's json module, so that
// numbers arrive exactly as printed by the CLI's --json.
template <class Json>
py::object to_python(const Json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}
// A Python value as JSON text (json.dumps; numpy arrays and scalars through tolist()/item()).
std::string to_json_text(const py::handle& value);

}  // namespace lucent::python
