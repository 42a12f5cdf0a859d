// frame_summary.h: per-frame timings and statistics (lucent::FrameTimings) summarised over frames, and as JSON:
// what `lucent render` prints and writes with --timings-json, what `lucent bench` records. Generic over
// methods: passes and statistics are whatever the frames carry.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "lucent/renderer.h"

namespace lucent::stats {

struct Spread {
  double median = 0.0, min = 0.0, max = 0.0;
  std::size_t count = 0;  // values summarised
};
Spread spread_of(std::vector<double> values);

struct NamedSpread {
  std::string name;
  std::string unit;
  Spread spread;
};

struct FrameSummary {
  std::size_t frames = 0;
  Spread total_ms;                   // over all frames
  std::vector<NamedSpread> passes;   // first-seen order; each over the frames that ran it (count says how many)
  std::vector<NamedSpread> stats;    // first-seen order; over the frames that reported it
};
FrameSummary summarize(std::span<const FrameTimings> frames);

// {"frames": [{"frame": n, "total_ms": t, "passes": {"name": ms, ...}, "stats": {"name": value, ...}}, ...]}
std::string timings_json(std::span<const FrameTimings> frames);

// The summary as text: one line per pass (median ms, and in how many frames it ran when not all), the total,
// then the statistics' medians.
std::string format_summary(const FrameSummary& summary, const std::string& device);

}  // namespace lucent::stats
