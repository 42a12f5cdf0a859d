// error.h: lucent's user-error channel. Bad input (a scene file, a material parameter, a mesh, a missing GL
// feature, a shader that does not compile) throws lucent::Error with one line that names the input. Errors
// are thrown at load, compile and context creation, never per frame.
#pragma once
#include <stdexcept>
#include <string>

namespace lucent {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lucent
