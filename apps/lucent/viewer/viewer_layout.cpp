// viewer_layout.cpp: see viewer_layout.h.
#include "viewer/viewer_layout.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace lucent::viewer {

int panel_width_for_window(int window_width, int wanted) {
  return std::max(std::min(wanted, window_width / 2), std::min(160, window_width));
}

PixelRect fit_view(glm::ivec2 image, const PixelRect& area) {
  if (image.x <= 0 || image.y <= 0 || area.width <= 0 || area.height <= 0) return {area.x, area.y, 0, 0};
  const double scale = std::min(static_cast<double>(area.width) / image.x, static_cast<double>(area.height) / image.y);
  const int width = std::clamp(static_cast<int>(std::lround(image.x * scale)), 1, area.width);
  const int height = std::clamp(static_cast<int>(std::lround(image.y * scale)), 1, area.height);
  return {area.x + (area.width - width) / 2, area.y + (area.height - height) / 2, width, height};
}

glm::ivec2 initial_window_size(glm::ivec2 view, int panel_width, int min_height) {
  const int scale = std::max(1, (min_height + view.y - 1) / std::max(view.y, 1));
  return {panel_width + view.x * scale, view.y * scale};
}

void KeyQueue::push(int key, bool pressed) {
  if (pressed && presses_.size() < kLimit) presses_.push_back(key);
}

std::vector<int> KeyQueue::take_presses() {
  std::vector<int> keys(presses_.begin(), presses_.end());
  presses_.clear();
  return keys;
}

void FrameClock::frame_done(double seconds) {
  if (!(seconds > 0.0)) return;
  seconds_per_frame_ = frames_ == 0 ? seconds : 0.8 * seconds_per_frame_ + 0.2 * seconds;
  ++frames_;
}

std::string FrameClock::rate_text() const {
  if (frames_ == 0) return "measuring";
  if (seconds_per_frame_ >= 1.0) return fmt::format("{:.1f} s/frame", seconds_per_frame_);
  return fmt::format("{:.1f} frames/s", 1.0 / seconds_per_frame_);
}

std::string frame_status_text(const FrameStatus& s) {
  if (!s.rendering)
    return fmt::format("idle: {} frame{} accumulated", s.frames_accumulated, s.frames_accumulated == 1 ? "" : "s");
  const int frame = s.frames_accumulated + 1;
  if (s.seconds_per_frame <= 0.0)
    return fmt::format("rendering frame {} (the first frame also builds what the method precomputes)", frame);
  std::string text = fmt::format("rendering frame {} (about {} a frame", frame,
                                 s.seconds_per_frame >= 1.0 ? fmt::format("{:.1f} s", s.seconds_per_frame)
                                                            : fmt::format("{:.0f} ms", 1e3 * s.seconds_per_frame));
  if (!s.slowest_pass.empty()) text += fmt::format("; pass '{}' {:.0f} ms of it", s.slowest_pass, s.slowest_pass_ms);
  return text + ")";
}

}  // namespace lucent::viewer
