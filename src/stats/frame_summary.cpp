// frame_summary.cpp: see frame_summary.h.
#include "stats/frame_summary.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace lucent::stats {
namespace {

NamedSpread& entry(std::vector<NamedSpread>& list, std::vector<std::vector<double>>& values, const std::string& name,
                   const std::string& unit, std::size_t& index) {
  auto it = std::find_if(list.begin(), list.end(), [&](const NamedSpread& s) { return s.name == name; });
  index = static_cast<std::size_t>(it - list.begin());
  if (it == list.end()) {
    list.push_back({name, unit, {}});
    values.emplace_back();
  }
  return list[index];
}

std::string number(double value) {
  if (value == std::floor(value) && std::fabs(value) < 1e15) return fmt::format("{:.0f}", value);
  return fmt::format("{:.4g}", value);
}

}  // namespace

Spread spread_of(std::vector<double> values) {
  Spread s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  std::size_t mid = values.size() / 2;
  s.median = values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
  s.min = values.front();
  s.max = values.back();
  return s;
}

FrameSummary summarize(std::span<const FrameTimings> frames) {
  FrameSummary summary;
  summary.frames = frames.size();
  std::vector<double> totals;
  std::vector<std::vector<double>> pass_values, stat_values;
  for (const FrameTimings& f : frames) {
    totals.push_back(f.total_ms);
    for (const PassTiming& p : f.passes) {
      std::size_t i = 0;
      entry(summary.passes, pass_values, p.name, "ms", i);
      pass_values[i].push_back(p.ms);
    }
    for (const FrameStatistic& s : f.stats) {
      std::size_t i = 0;
      entry(summary.stats, stat_values, s.name, s.unit, i);
      stat_values[i].push_back(s.value);
    }
  }
  summary.total_ms = spread_of(totals);
  for (std::size_t i = 0; i < summary.passes.size(); ++i) summary.passes[i].spread = spread_of(pass_values[i]);
  for (std::size_t i = 0; i < summary.stats.size(); ++i) summary.stats[i].spread = spread_of(stat_values[i]);
  return summary;
}

std::string timings_json(std::span<const FrameTimings> frames) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const FrameTimings& f : frames) {
    nlohmann::ordered_json passes = nlohmann::ordered_json::object(), stats = nlohmann::ordered_json::object();
    for (const PassTiming& p : f.passes) passes[p.name] = p.ms;
    for (const FrameStatistic& s : f.stats) stats[s.name] = s.value;
    list.push_back({{"frame", f.frame}, {"total_ms", f.total_ms}, {"passes", passes}, {"stats", stats}});
  }
  return nlohmann::ordered_json{{"frames", list}}.dump(1) + "\n";
}

std::string format_summary(const FrameSummary& summary, const std::string& device) {
  std::string out = fmt::format("GPU time per frame, median of {} frame(s), on {}:\n", summary.frames, device);
  for (const NamedSpread& p : summary.passes) {
    out += fmt::format("  {:<22} {:10.3f} ms", p.name, p.spread.median);
    if (p.spread.count != summary.frames) out += fmt::format("  (ran in {} of {} frames)", p.spread.count, summary.frames);
    out += "\n";
  }
  out += fmt::format("  {:<22} {:10.3f} ms\n", "total", summary.total_ms.median);
  if (!summary.stats.empty()) {
    out += "  statistics (median):";
    for (const NamedSpread& s : summary.stats)
      out += fmt::format(" {} {}{}", s.name, number(s.spread.median), s.unit.empty() ? "" : " " + s.unit);
    out += "\n";
  }
  return out;
}

}  // namespace lucent::stats
