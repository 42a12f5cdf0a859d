// progress_bar.cpp: draws "label [#####.....] 5/10  2.1 s left".
#include "progress_bar.h"

#include <cstdio>

namespace lucent::cli {

ProgressBar::ProgressBar(std::string label, int total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()), enabled_(total > 1) {}

void ProgressBar::update(int done) {
  if (!enabled_) return;
  constexpr int kWidth = 30;
  int filled = done * kWidth / total_;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (done < total_ && elapsed - last_draw_ < 0.25) return;  // redraw at most four times a second
  last_draw_ = elapsed;
  double left = done > 0 ? elapsed * (total_ - done) / done : 0.0;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r%s [%s] %d/%d  %.1f s left ", label_.c_str(), bar.c_str(), done, total_, left);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

}  // namespace lucent::cli
