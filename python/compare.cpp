// compare.cpp: lucent.compare: the errors `lucent compare --json` prints, on linear and tone-mapped values.
#include <fmt/format.h>

#include "arguments.h"
#include "bindings.h"
#include "image/image_error_json.h"
#include "image/image_metrics.h"
#include "image_arrays.h"
#include "lucent/error.h"
#include "params/argument_ranges.h"

namespace lucent::python {
namespace {

void check_same_size(const ImageRGBA32F& a, const ImageRGBA32F& b, const char* a_name, const char* b_name) {
  if (a.width != b.width || a.height != b.height)
    throw Error(fmt::format("{} is {}x{} but {} is {}x{}; compare needs images of one size", a_name, a.width,
                            a.height, b_name, b.width, b.height));
}

py::object compare(const py::handle& a_array, const py::handle& b_array, const py::handle& se_array,
                   const py::handle& exposure_stops) {
  const auto exposure =
      static_cast<float>(number_argument(exposure_stops, argument_ranges::kExposureStops, "exposure"));
  const ImageRGBA32F a = from_array(a_array, "a"), b = from_array(b_array, "b");
  check_same_size(a, b, "a", "b");
  std::optional<ImageRGBA32F> se;
  if (!se_array.is_none()) se = from_array(se_array, "standard_error");
  if (se) check_same_size(*se, b, "standard_error", "b");
  nlohmann::json result = {{"linear", to_json(image_error(a, b, se ? &*se : nullptr))},
                           {"display", to_json(display_error(a, b, exposure))}};
  return to_python(result);
}

}  // namespace

void bind_compare(py::module_& m) {
  m.def("compare", &compare, py::arg("a"), py::arg("b"), py::arg("standard_error") = py::none(),
        py::arg("exposure") = 0.0,
        "Error of image a against reference b (arrays (height, width, 3)) as `lucent compare --json` reports it: "
        "{\"linear\": {...}, \"display\": {...}} with rmse (per channel), rmse_rgb, relative_mse, mean_error, "
        "mean_error_se, psnr_db (None when infinite or undefined; psnr says which), reference_noise_rms; standard_error is the reference's (as from "
        "lucent.reference), exposure [stops] the tone mapping of the display comparison.");
}

}  // namespace lucent::python
