// image_arrays.cpp: ImageRGBA32F <-> numpy (height, width, 3) float32, and the image files as arrays.
#include "image_arrays.h"

#include <fmt/format.h>

#include "arguments.h"
#include "bindings.h"
#include "image/image_metrics.h"
#include "io/file_path_check.h"
#include "lucent/error.h"
#include "lucent/output_file.h"
#include "params/argument_ranges.h"

namespace lucent::python {

pybind11::array_t<float> to_array(const ImageRGBA32F& image) {
  py::array_t<float> array({image.height, image.width, 3});
  auto out = array.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) out(y, x, c) = image.at(x, y)[c];
  return array;
}

ImageRGBA32F from_array(const pybind11::handle& object, const std::string& what) {
  using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;
  Floats array = Floats::ensure(object);
  if (!array) throw Error(fmt::format("{}: expected a numeric array of shape (height, width, 3)", what));
  if (array.ndim() != 3 || (array.shape(2) != 3 && array.shape(2) != 4) || array.shape(0) < 1 || array.shape(1) < 1) {
    py::tuple shape(array.ndim());
    for (py::ssize_t i = 0; i < array.ndim(); ++i) shape[static_cast<std::size_t>(i)] = array.shape(i);
    throw Error(fmt::format("{}: expected an array of shape (height, width, 3) or (height, width, 4), got {}", what,
                            py::repr(shape).cast<std::string>()));
  }
  ImageRGBA32F image;
  image.height = static_cast<int>(array.shape(0)), image.width = static_cast<int>(array.shape(1));
  image.pixels.assign(4 * static_cast<std::size_t>(image.width) * image.height, 1.0f);
  const int channels = static_cast<int>(array.shape(2));
  auto in = array.unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y)[c] = in(y, x, c);
  return image;
}

namespace {

// A file written by write_exr or write_png: a name that can be a file's (no NUL byte) and says the format written
// ("x.png" does not get EXR bytes), as the command line checks its outputs.
void check_image_output(const std::string& path, std::string_view extension) {
  check_file_path(path);
  check_outputs({{path, "path", {extension}}}, {});
}

}  // namespace

void bind_images(py::module_& m) {
  m.def("read_exr", [](const std::string& path) { return to_array(read_exr(path)); }, py::arg("path"),
        "Linear RGB of an EXR file as float32 (height, width, 3); alpha is dropped.");
  m.def(
      "write_exr",
      [](const std::string& path, const py::handle& image) {
        check_image_output(path, ".exr");
        write_exr(path, from_array(image, "image"));
      },
      py::arg("path"), py::arg("image"), "Writes (height, width, 3 or 4) linear values as an RGBA float EXR.");
  m.def(
      "write_png",
      [](const std::string& path, const py::handle& image, const py::handle& exposure) {
        check_image_output(path, ".png");
        const double stops = number_argument(exposure, argument_ranges::kExposureStops, "exposure");
        write_png(path, to_display(from_array(image, "image"), static_cast<float>(stops)));
      },
      py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0,
      "Tone-maps linear radiance (exposure in stops, ACES, sRGB) as lucent render does and writes a PNG.");
}

}  // namespace lucent::python
