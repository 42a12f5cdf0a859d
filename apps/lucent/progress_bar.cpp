// progress_bar.cpp: see progress_bar.h.
#include "progress_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

namespace lucent::cli {

ProgressBar::ProgressBar(std::string label, int total, std::string unit)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      start_(std::chrono::steady_clock::now()),
      enabled_(total > 1) {}

double ProgressBar::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressBar::update(int done) {
  if (!enabled_) return;
  const double seconds = elapsed();
  std::string left = done > 0 ? format_seconds(seconds * (total_ - done) / done) + " left" : "time left not known yet";
  const std::string counts = fmt::format("{}/{}{}{}", done, total_, unit_.empty() ? "" : " ", unit_);
  draw(static_cast<double>(done) / total_, fmt::format("{}  {} elapsed, {}", counts, format_seconds(seconds), left));
}

void ProgressBar::update_fraction(double fraction) {
  if (!enabled_) return;
  const double seconds = elapsed();
  std::string left = fraction > 0.0 ? format_seconds(seconds * (1.0 - fraction) / fraction) + " left" : "";
  draw(fraction, fmt::format("{:.1f}%  {} elapsed{}{}", 100.0 * std::clamp(fraction, 0.0, 1.0),
                             format_seconds(seconds), left.empty() ? "" : ", ", left));
}

void ProgressBar::draw(double fraction, const std::string& text) {
  if (!enabled_) return;
  constexpr int kWidth = 30;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const double seconds = elapsed();
  if (fraction < 1.0 && seconds - last_draw_ < 0.25) return;  // redraw at most four times a second
  last_draw_ = seconds;
  std::string bar(static_cast<std::size_t>(std::lround(fraction * kWidth)), '#');
  bar.resize(kWidth, '.');
  std::string line = fmt::format("{} [{}] {}", label_, bar, text);
  const std::size_t width = line.size();
  if (width < last_width_) line.append(last_width_ - width, ' ');
  last_width_ = width;
  std::fprintf(stderr, "\r%s", line.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

std::string format_seconds(double seconds) {
  if (!(seconds >= 0.0)) return "? s";
  if (seconds < 60.0) return fmt::format("{:.1f} s", seconds);
  const long long whole = std::llround(seconds);
  if (whole < 3600) return fmt::format("{} min {:02d} s", whole / 60, whole % 60);
  return fmt::format("{} h {:02d} min", whole / 3600, (whole % 3600) / 60);
}

}  // namespace lucent::cli
