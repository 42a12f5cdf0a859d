// image_arrays.h: images as numpy arrays: float32, shape (height, width, 3), linear RGB, the top row first.
#pragma once
#include <string>

#include <pybind11/numpy.h>

#include "lucent/image.h"

namespace lucent::python {

pybind11::array_t<float> to_array(const ImageRGBA32F& image);  // alpha dropped
// From an array of shape (height, width, 3) or (height, width, 4) of numbers (converted to float32; alpha 1 when
// absent). Throws lucent::Error("<what>: ...") for another shape.
ImageRGBA32F from_array(const pybind11::handle& array, const std::string& what);

}  // namespace lucent::python
