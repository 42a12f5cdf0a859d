// viewer_layout.h: the viewer's window logic that needs no window: where the panel and the view go for a window
// size, the key presses queued between frames, the frame clock and the frame-in-progress line. Pure functions and
// small classes, tested in tests/cpu/test_viewer_layout.cpp.
//
// The view is rendered at its asked size (--width/--height, else the scene's render.width/height) and scaled to fit
// the space right of the panel, aspect kept, centred (letterboxed). The render size is not made to follow the window:
// on a software rasterizer it sets the cost of every frame (a 320x240 frame can take 15 s on llvmpipe), and it is
// the size the screenshot and "save scene as" record, which `lucent render` reproduces. The window opens at an
// integer multiple of that size, so the image fills it with whole pixels.
#pragma once
#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lucent::viewer {

// A rectangle in window pixels, y from the top.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// The panel's width in a window `window_width` wide: the width asked, but never more than half the window (the
// view keeps the rest) nor less than 160 pixels.
int panel_width_for_window(int window_width, int wanted);

// `image` scaled to fit `area`, aspect kept, centred; an empty image or area gives an empty rectangle.
PixelRect fit_view(glm::ivec2 image, const PixelRect& area);

// The window's size for a view of `view` pixels beside a panel `panel_width` wide: the view at the smallest
// integer scale whose height reaches `min_height` (room for the panel), the panel beside it.
glm::ivec2 initial_window_size(glm::ivec2 view, int panel_width, int min_height = 480);

// Key presses as the window system reports them (GLFW's key callback), kept until the next frame takes them: a tap
// shorter than a frame is still seen at 0.1 frames/s, where polling a key's state once a frame misses it.
class KeyQueue {
 public:
  // A GLFW key event: `pressed` true for a press (a repeat counts as a press), false for a release.
  void push(int key, bool pressed);
  // The keys pressed since the last call, in order (a key pressed twice appears twice).
  std::vector<int> take_presses();

 private:
  static constexpr std::size_t kLimit = 256;  // presses beyond it (no frame for minutes) are dropped
  std::deque<int> presses_;
};

// Frame times measured on the wall clock, from one finished frame to the next (a GPU frame's timings arrive a few
// frames late): the rate shown is that of the frames actually rendered, not decayed from zero.
class FrameClock {
 public:
  // A frame finished `seconds` after the previous one.
  void frame_done(double seconds);
  // Seconds per frame, smoothed (the first frame's time as it is); 0 before any frame.
  double seconds_per_frame() const { return seconds_per_frame_; }
  // "12.5 frames/s", "15.2 s/frame" (slower than a frame a second), "measuring" before a frame.
  std::string rate_text() const;

 private:
  double seconds_per_frame_ = 0.0;
  int frames_ = 0;
};

// What the frame-in-progress line says.
struct FrameStatus {
  int frames_accumulated = 0;       // frames in the image on screen
  bool rendering = false;           // a frame is being rendered now (false: converged or nothing to render)
  double seconds_per_frame = 0.0;   // of the frames so far, 0 when none
  std::string slowest_pass;         // the costliest pass of the last timed frame ("" when none reported yet)
  double slowest_pass_ms = 0.0;
};

// "rendering frame 3 (about 15.2 s a frame; pass 'integrate' 14100 ms of the last)", "rendering frame 1 (the first
// frame also builds the method's maps)", "idle: 64 frames accumulated".
std::string frame_status_text(const FrameStatus& status);

}  // namespace lucent::viewer
