// progress_bar.h: a one-line progress bar on stderr with the time left.
#pragma once
#include <chrono>
#include <string>

namespace lucent::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total);
  void update(int done);
  void finish();

 private:
  std::string label_;
  int total_;
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  double last_draw_ = -1.0;  // seconds since start of the last redraw
};

}  // namespace lucent::cli
