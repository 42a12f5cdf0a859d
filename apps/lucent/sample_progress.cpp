// sample_progress.cpp: see sample_progress.h.
#include "sample_progress.h"

#include <algorithm>

#include <fmt/format.h>

#include "progress_bar.h"

namespace lucent::cli {

std::vector<int> reference_pass_ends(int first_sample, int wanted) {
  std::vector<int> ends;
  for (int done = 0; done < wanted;) {
    done += std::min(wanted - done, std::max(1, (first_sample + done) / 8));
    ends.push_back(done);
  }
  return ends;
}

SampleEta::SampleEta(int first_sample, int wanted)
    : pass_ends_(reference_pass_ends(first_sample, wanted)), wanted_(wanted) {}

void SampleEta::update(double fraction, double seconds) {
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  // The latest pass end the run has reached (its report after the pass's last row is exactly end / wanted).
  const double samples = fraction_ * wanted_ + 1e-6;
  int done = done_;
  for (int end : pass_ends_)
    if (end <= samples) done = std::max(done, end);
  if (done == done_) return;
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
  const int first_pass = pass_ends_.empty() ? 1 : pass_ends_.front();
  return counts + fmt::format(", first pass {:.0f}% done", 100.0 * std::min(1.0, fraction_ * wanted_ / first_pass));
}

}  // namespace lucent::cli
