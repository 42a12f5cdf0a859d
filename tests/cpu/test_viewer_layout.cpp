// test_viewer_layout.cpp: the viewer's window logic without a window (apps/lucent/viewer/viewer_layout.h): the
// view scaled to fit beside a panel sized from the window, key taps queued between slow frames, an honest frame
// rate and frame-in-progress line; and the material editor's albedo / mean free path (viewer/material_artist.h).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lucent/material.h"
#include "viewer/material_artist.h"
#include "viewer/viewer_layout.h"

namespace lucent::viewer {
namespace {

// A 320x240 view in a 700x480 window with a 380-pixel panel asked: the panel takes half the window (350), the view
// is scaled by 350 / 320 into the rest and centred vertically: no black band left under a top-aligned image.
TEST(ViewerLayout, TheViewFillsTheSpaceBesideThePanel) {
  const int panel = panel_width_for_window(700, 380);
  EXPECT_EQ(panel, 350);
  const PixelRect view = fit_view({320, 240}, {panel, 0, 700 - panel, 480});
  EXPECT_EQ(view.x, 350);
  EXPECT_EQ(view.width, 350);
  EXPECT_EQ(view.height, 263);  // 240 * 350 / 320 = 262.5
  EXPECT_EQ(view.y, (480 - 263) / 2);
  // A wide window: height-limited, centred horizontally.
  const PixelRect wide = fit_view({320, 240}, {380, 0, 1000, 480});
  EXPECT_EQ(wide.width, 640);
  EXPECT_EQ(wide.height, 480);
  EXPECT_EQ(wide.x, 380 + (1000 - 640) / 2);
  EXPECT_EQ(wide.y, 0);
  EXPECT_EQ(fit_view({320, 240}, {380, 0, 0, 480}).width, 0);
  EXPECT_EQ(panel_width_for_window(1200, 380), 380);
  EXPECT_EQ(panel_width_for_window(200, 380), 160);
}

// The window opens at the smallest integer scale of the view that gives the panel 480 rows: the image fills it with
// whole pixels.
TEST(ViewerLayout, TheWindowOpensAtAnIntegerScaleOfTheView) {
  EXPECT_EQ(initial_window_size({320, 240}, 380), glm::ivec2(380 + 640, 480));
  EXPECT_EQ(initial_window_size({160, 120}, 240), glm::ivec2(240 + 640, 480));
  EXPECT_EQ(initial_window_size({640, 480}, 380), glm::ivec2(380 + 640, 480));
  EXPECT_EQ(initial_window_size({800, 600}, 380), glm::ivec2(380 + 800, 600));
  EXPECT_EQ(initial_window_size({100, 300}, 380), glm::ivec2(380 + 200, 600));
}

// A tap (press and release between two frames) is seen at the next frame, however long the frame took; releases
// are not presses; two taps are two presses.
TEST(ViewerLayout, KeyTapsBetweenFramesAreNotLost) {
  KeyQueue keys;
  constexpr int kP = 80, kR = 82;
  keys.push(kP, true);
  keys.push(kP, false);
  keys.push(kR, true);
  keys.push(kR, false);
  keys.push(kR, true);
  keys.push(kR, false);
  EXPECT_EQ(keys.take_presses(), (std::vector<int>{kP, kR, kR}));
  EXPECT_TRUE(keys.take_presses().empty());
  for (int i = 0; i < 1000; ++i) keys.push(kR, true);
  EXPECT_EQ(keys.take_presses().size(), 256u);
}

// Frames of 15 s read as 15 s a frame from the first one (a rate smoothed up from zero read "0.0 frames/s").
TEST(ViewerLayout, FrameRateIsMeasuredFromTheFirstFrame) {
  FrameClock clock;
  EXPECT_EQ(clock.rate_text(), "measuring");
  clock.frame_done(15.0);
  EXPECT_DOUBLE_EQ(clock.seconds_per_frame(), 15.0);
  EXPECT_EQ(clock.rate_text(), "15.0 s/frame");
  clock.frame_done(5.0);
  EXPECT_DOUBLE_EQ(clock.seconds_per_frame(), 0.8 * 15.0 + 0.2 * 5.0);
  FrameClock fast;
  fast.frame_done(0.04);
  EXPECT_EQ(fast.rate_text(), "25.0 frames/s");
}

TEST(ViewerLayout, TheStatusLineSaysWhichFrameIsRendering) {
  FrameStatus status;
  status.rendering = true;
  EXPECT_EQ(frame_status_text(status), "rendering frame 1 (the first frame also builds what the method precomputes)");
  status.frames_accumulated = 2;
  status.seconds_per_frame = 15.2;
  status.slowest_pass = "integrate";
  status.slowest_pass_ms = 14100.0;
  EXPECT_EQ(frame_status_text(status), "rendering frame 3 (about 15.2 s a frame; pass 'integrate' 14100 ms of it)");
  status.rendering = false;
  status.frames_accumulated = 64;
  EXPECT_EQ(frame_status_text(status), "idle: 64 frames accumulated");
  status.frames_accumulated = 1;
  EXPECT_EQ(frame_status_text(status), "idle: 1 frame accumulated");
}

// The albedo / mfp editor shows a material's values and turns edits back into coefficients: the mfp is
// 1 / sigma_t, and an edit keeps the other band values (round trip), changes sigma_t as asked, and an albedo the
// model cannot reach is refused with the material unchanged.
TEST(ViewerMaterialArtist, AlbedoAndMeanFreePathRoundTrip) {
  Material m;
  m.sigma_a = {0.01f, 0.05f, 0.2f};
  m.sigma_s = {1.0f, 0.8f, 0.6f};
  m.eta = 1.3f;
  const std::optional<ArtistParameters> artist = artist_parameters_of(m);
  ASSERT_TRUE(artist.has_value());
  EXPECT_NEAR(artist->mfp_mm.x, 1.0 / 1.01, 1e-6);
  EXPECT_NEAR(artist->mfp_mm.z, 1.0 / 0.8, 1e-6);
  EXPECT_GT(artist->albedo.x, artist->albedo.y);  // less absorption, more light back
  EXPECT_GT(artist->albedo.y, artist->albedo.z);
  Material same = m;
  ASSERT_EQ(apply_artist_parameters(same, *artist), "");
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(same.sigma_a[c], m.sigma_a[c], 1e-3 * m.sigma_a[c] + 1e-6) << c;
    EXPECT_NEAR(same.sigma_s[c], m.sigma_s[c], 1e-3 * m.sigma_s[c]) << c;
  }
  ArtistParameters longer = *artist;
  longer.mfp_mm *= 2.0f;  // twice the mean free path: half the extinction, the same albedo
  Material stretched = m;
  ASSERT_EQ(apply_artist_parameters(stretched, longer), "");
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(stretched.sigma_t()[c], 0.5f * m.sigma_t()[c], 1e-3f * m.sigma_t()[c]) << c;
  ArtistParameters impossible = *artist;
  impossible.albedo.x = 1.5f;
  Material kept = m;
  EXPECT_NE(apply_artist_parameters(kept, impossible), "");
  EXPECT_EQ(kept.sigma_a, m.sigma_a);
  Material clear = m;
  clear.sigma_a.y = 0.0f;
  EXPECT_FALSE(artist_parameters_of(clear).has_value());
}

}  // namespace
}  // namespace lucent::viewer
