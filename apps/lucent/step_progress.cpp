// step_progress.cpp: see step_progress.h.
#include "step_progress.h"

#include <algorithm>
#include <cmath>

namespace lucent::cli {

void StepProgress::operator()(std::string_view step, double fraction) {
  auto now = std::chrono::steady_clock::now();
  if (step != step_ || fraction <= 0.0) {  // a new step (or the same one again, in a later rebuild)
    if (bar_) bar_->finish();
    bar_.reset();
    step_ = step;
    start_ = now;
  }
  int done = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * kTicks));
  if (!bar_ && done < kTicks && std::chrono::duration<double>(now - start_).count() >= show_after_s_)
    bar_.emplace(step_, kTicks);
  if (!bar_) return;
  bar_->update_fraction(static_cast<double>(done) / kTicks);
  if (done == kTicks) {
    bar_->finish();
    bar_.reset();
  }
}

}  // namespace lucent::cli
