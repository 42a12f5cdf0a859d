// step_progress.h: the Renderer's precompute progress (lucent::RenderProgress) as a ProgressBar per step, shown
// only once a step has taken longer than a moment (a cache hit or a quick step prints nothing).
#pragma once
#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "progress_bar.h"

namespace lucent::cli {

class StepProgress {
 public:
  explicit StepProgress(double show_after_s = 0.5) : show_after_s_(show_after_s) {}
  void operator()(std::string_view step, double fraction);

 private:
  static constexpr int kTicks = 1000;
  double show_after_s_;
  std::string step_;
  std::chrono::steady_clock::time_point start_;
  std::optional<ProgressBar> bar_;
};

}  // namespace lucent::cli
