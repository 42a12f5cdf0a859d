// progress_bar.h: a one-line progress bar on stderr with its units, the time elapsed and the time left:
//   rendering [#####.........................] 5/30 frames  2.1 s elapsed, 10.5 s left
#pragma once
#include <chrono>
#include <string>

namespace lucent::cli {

class ProgressBar {
 public:
  // `unit` follows the counts ("frames"); `total` <= 1 draws nothing (quiet).
  ProgressBar(std::string label, int total, std::string unit = "");
  // `done` of `total`; the time left assumes every unit takes as long as those done.
  void update(int done);
  // A fraction of the work done, shown as a percentage, the time left from it.
  void update_fraction(double fraction);
  // A bar filled to `fraction`, then `text` (the caller's counts and time left); redrawn at most four times a second
  // unless `fraction` is 1.
  void draw(double fraction, const std::string& text);
  void finish();
  // Seconds since the bar was made.
  double elapsed() const;

 private:
  std::string label_;
  int total_;
  std::string unit_;
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  double last_draw_ = -1.0;  // seconds since start of the last redraw
  std::size_t last_width_ = 0;  // characters of the last line drawn, blanked when a shorter one replaces it
};

// "12.3 s", "4 min 05 s", "2 h 07 min": a duration as a person reads it.
std::string format_seconds(double seconds);

}  // namespace lucent::cli
