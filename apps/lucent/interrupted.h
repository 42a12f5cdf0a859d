// interrupted.h: a command that a signal stopped after it saved what it could (a reference's completed passes).
// main prints "lucent: <message>" and exits 128 + the signal's number, the status a shell gives a process that the
// signal ended.
#pragma once
#include <string>

#include "lucent/error.h"

namespace lucent::cli {

class Interrupted : public Error {
 public:
  Interrupted(int signal, const std::string& message) : Error(message), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

}  // namespace lucent::cli
