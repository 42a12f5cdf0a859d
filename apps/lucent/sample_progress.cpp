// sample_progress.cpp: see sample_progress.h.
#include "sample_progress.h"

#include <algorithm>

#include <fmt/format.h>

#include "progress_bar.h"
#include "reference/reference_renderer.h"

namespace lucent::cli {

SampleEta::SampleEta(int first_sample, int wanted)
    : first_pass_(std::max(1, reference::reference_pass_size(first_sample, wanted))), wanted_(wanted) {}

void SampleEta::update(double fraction) { fraction_ = std::clamp(fraction, 0.0, 1.0); }

void SampleEta::pass_completed(int samples_done, double seconds) {
  const int done = std::clamp(samples_done, 0, wanted_);
  fraction_ = std::max(fraction_, static_cast<double>(done) / std::max(1, wanted_));
  if (done <= done_) return;
  if (done_ == 0) {
    first_end_seconds_ = seconds;
    first_end_samples_ = done;
  }
  done_ = done;
  last_end_seconds_ = seconds;
}

std::optional<double> SampleEta::seconds_left(double seconds) const {
  if (done_ == 0) return std::nullopt;
  if (done_ >= wanted_) return 0.0;
  const double per_sample = done_ > first_end_samples_
                                ? (last_end_seconds_ - first_end_seconds_) / (done_ - first_end_samples_)
                                : first_end_seconds_ / first_end_samples_;
  return std::max(0.0, per_sample * (wanted_ - done_) - (seconds - last_end_seconds_));
}

std::string SampleEta::text(double seconds) const {
  std::string counts = fmt::format("{}/{} spp  {} elapsed", done_, wanted_, format_seconds(seconds));
  if (const std::optional<double> left = seconds_left(seconds)) return counts + ", " + format_seconds(*left) + " left";
  return counts + fmt::format(", first pass {:.0f}% done", 100.0 * std::min(1.0, fraction_ * wanted_ / first_pass_));
}

}  // namespace lucent::cli
