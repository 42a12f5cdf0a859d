// sample_progress.h: a reference's progress in samples per pixel, with a time left measured on completed samples:
//   volpath [#########.....................] 5/16 spp  12.3 s elapsed, 27.1 s left
//
// reference::render_reference renders passes over the whole image (reference::reference_pass_size), reports the
// fraction of its run done after every chunk of rows and samples, and the samples done after every pass. Rows differ
// in cost (an object in the middle of the image, empty background at the top), so that fraction inside a pass says
// little about time: the time left here comes from the seconds per sample of the completed passes instead, and the
// passes' growth is in the count of samples left. Before the first pass ends no estimate is shown.
#pragma once
#include <optional>
#include <string>

namespace lucent::cli {

// The counts and times of a reference run that adds `wanted` samples per pixel to `first_sample` earlier ones, from
// its progress reports.
class SampleEta {
 public:
  SampleEta(int first_sample, int wanted);
  // A progress report (ReferenceSettings::progress): `fraction` of the run done.
  void update(double fraction);
  // A completed pass (ReferenceSettings::pass_done): `samples_done` samples per pixel of this run, at `seconds`
  // since the run started (setup included).
  void pass_completed(int samples_done, double seconds);
  // Samples per pixel of this run in completed passes.
  int samples_done() const { return done_; }
  int samples_wanted() const { return wanted_; }
  // Seconds left at `seconds` since the start; none before the first pass ends. The first pass's time includes the
  // setup (scene, ray-tracing structures), so the first estimate errs long; later ones use the passes after it.
  std::optional<double> seconds_left(double seconds) const;
  // "5/16 spp  12.3 s elapsed, 27.1 s left" (or "..., first pass 40% done" before a pass has ended).
  std::string text(double seconds) const;

 private:
  int first_pass_;  // samples per pixel of the run's first pass
  int wanted_;
  double fraction_ = 0.0;
  int done_ = 0;
  double first_end_seconds_ = -1.0;  // when the first pass ended
  int first_end_samples_ = 0;
  double last_end_seconds_ = -1.0;   // when the latest pass ended
};

}  // namespace lucent::cli
