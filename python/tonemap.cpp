// tonemap.cpp: lucent.tonemap: linear radiance to display values with the tone curve of `lucent render`'s
// tone-map pass (shared/tonemap.h, the code its compute shader runs): exposure, operator, sRGB encoding.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>
#include <pybind11/numpy.h>

#include "arguments.h"
#include "bindings.h"
#include "image_arrays.h"
#include "image/image_metrics.h"
#include "params/argument_ranges.h"
#include "shared/tonemap.h"

namespace lucent::python {
namespace {

int operator_of(const std::string& name) {
  if (name == "aces") return LUCENT_TONEMAP_ACES;
  if (name == "reinhard") return LUCENT_TONEMAP_REINHARD;
  if (name == "linear") return LUCENT_TONEMAP_LINEAR;
  throw py::value_error(fmt::format("operator: '{}' is not one of aces, reinhard, linear", name));
}

py::array tonemap(const py::handle& image_array, const py::handle& exposure_stops, const std::string& operator_name,
                  const py::handle& dtype) {
  const std::string type = py::str(py::dtype::from_args(py::reinterpret_borrow<py::object>(dtype)).attr("name"));
  if (type != "uint8" && type != "float32")
    throw py::value_error(fmt::format("dtype: {} is not uint8 or float32", type));
  const int op = operator_of(operator_name);
  const auto stops = static_cast<float>(number_argument(exposure_stops, argument_ranges::kExposureStops, "exposure"));
  const ImageRGBA32F image = from_array(image_array, "image");
  check_displayable(image, "image");  // a NaN has no display value: not 0, not NaN in silence
  const float scale = std::exp2(stops);
  // The curves square their input: past about 1e19 float overflows; 1e6 after exposure is white already.
  const float largest = 1e6f / scale;
  py::array_t<float> floats({image.height, image.width, 3});
  py::array_t<std::uint8_t> bytes({image.height, image.width, 3});
  auto f = floats.mutable_unchecked<3>();
  auto b = bytes.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.at(x, y);
      const glm::vec3 v = shader::tonemap(glm::min(glm::vec3(p[0], p[1], p[2]), glm::vec3(largest)), scale, op);
      for (int c = 0; c < 3; ++c) {
        f(y, x, c) = v[c];
        b(y, x, c) = static_cast<std::uint8_t>(std::lround(std::clamp(v[c], 0.0f, 1.0f) * 255.0f));
      }
    }
  if (type == "float32") return floats;
  return bytes;
}

}  // namespace

void bind_tonemap(py::module_& m) {
  m.def("tonemap", &tonemap, py::arg("image"), py::kw_only(), py::arg("exposure") = 0.0,
        py::arg("operator") = "aces", py::arg("dtype") = "uint8",
        "Linear radiance (height, width, 3 or 4) to display values as `lucent render` writes its PNG: times "
        "2^exposure [stops], the operator (\"aces\", \"reinhard\" or \"linear\", as render.tonemap), sRGB encoded. "
        "Returns uint8 (height, width, 3) for imshow, or float32 in [0, 1] with dtype=\"float32\".");
}

}  // namespace lucent::python
