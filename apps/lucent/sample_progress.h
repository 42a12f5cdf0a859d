// sample_progress.h: a reference's progress in samples per pixel, with a time left measured on completed samples:
//   volpath [#########.....................] 5/16 spp  12.3 s elapsed, 27.1 s left
//
// reference::render_reference renders passes over the whole image, each at most an eighth of the samples done before
// it (at least one), and reports the fraction of its run done after every chunk of rows. Rows differ in cost (an
// object in the middle of the image, empty background at the top), so that fraction inside a pass says little about
// time: the time left here comes from the seconds per sample of the completed passes instead, and the passes' growth
// is in the count of samples left. Before the first pass ends no estimate is shown.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace lucent::cli {

// The samples of this run done at the end of each pass of a run that adds `wanted` samples per pixel to
// `first_sample` earlier ones (reference_renderer.cpp's schedule).
std::vector<int> reference_pass_ends(int first_sample, int wanted);

// The counts and times of a reference run, from its progress reports.
class SampleEta {
 public:
  SampleEta(int first_sample, int wanted);
  // A progress report: `fraction` of the run done, `seconds` since the run started (setup included).
  void update(double fraction, double seconds);
  // Samples per pixel of this run in completed passes.
  int samples_done() const { return done_; }
  int samples_wanted() const { return wanted_; }
  // Seconds left at `seconds` since the start; none before the first pass ends. The first pass's time includes the
  // setup (scene, ray-tracing structures), so the first estimate errs long; later ones use the passes after it.
  std::optional<double> seconds_left(double seconds) const;
  // "5/16 spp  12.3 s elapsed, 27.1 s left" (or "..., first pass 40% done" before a pass has ended).
  std::string text(double seconds) const;

 private:
  std::vector<int> pass_ends_;
  int wanted_;
  double fraction_ = 0.0;
  int done_ = 0;
  double first_end_seconds_ = -1.0;  // when the first pass ended
  int first_end_samples_ = 0;
  double last_end_seconds_ = -1.0;   // when the latest pass ended
};

}  // namespace lucent::cli
