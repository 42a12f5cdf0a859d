// module.cpp: the `lucent` Python module: scenes, real-time renders as numpy arrays, CPU references, image
// comparison, BSSRDF evaluation and the catalogues of methods and materials, all through the C++ library
// (docs/python.md).
#include "bindings.h"
#include "python_warnings.h"

PYBIND11_MODULE(lucent, m) {
  m.doc() = "lucent: real-time translucent materials with physically based subsurface scattering";
  using namespace lucent::python;
  bind_errors(m);
  bind_warnings(m);
  bind_context(m);
  bind_images(m);
  bind_tonemap(m);
  bind_scene(m);
  bind_render(m);
  bind_renderer(m);
  bind_reference(m);
  bind_compare(m);
  bind_bssrdf(m);
  bind_methods(m);
  bind_materials(m);
}
