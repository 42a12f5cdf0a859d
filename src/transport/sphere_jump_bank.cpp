// sphere_jump_bank.cpp: see sphere_jump_bank.h.
#include "transport/sphere_jump_bank.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace lucent::reference {

SphereJumpBank::SphereJumpBank(std::uint64_t seed, int records_per_level)
    : seed_(seed), records_per_level_(records_per_level) {
  if (records_per_level < 1) throw std::invalid_argument("SphereJumpBank: at least one record per level");
}

int SphereJumpBank::record_count(int level) const {
  return shader::sphere_walk_record_count(level, records_per_level_);
}

std::vector<shader::SphereWalkGPU> SphereJumpBank::generate(std::uint64_t seed, int sample, float g, int level,
                                                            int count) {
  std::vector<shader::SphereWalkGPU> records(static_cast<std::size_t>(count));
  const float radius = shader::sphere_jump_level_radius(level);
  const auto seed_low = static_cast<std::uint32_t>(seed), seed_high = static_cast<std::uint32_t>(seed >> 32u);
  for (int i = 0; i < count; ++i) {
    const std::uint32_t record_seed =
        shader::seed_from(seed_low, seed_high ^ (static_cast<std::uint32_t>(level) << 24u),
                          static_cast<std::uint32_t>(sample), static_cast<std::uint32_t>(i));
    records[static_cast<std::size_t>(i)] = shader::sphere_walk(radius, g, record_seed);
  }
  return records;
}

std::span<const shader::SphereWalkGPU> SphereJumpBank::records(int sample, float g, int level) const {
  Level* entry = nullptr;
  {
    const std::lock_guard lock(mutex_);
    std::unique_ptr<Level>& slot = banks_[{sample, std::bit_cast<std::uint32_t>(g), level}];
    if (!slot) slot = std::make_unique<Level>();
    entry = slot.get();
  }
  std::call_once(entry->once, [&] { entry->records = generate(seed_, sample, g, level, record_count(level)); });
  return entry->records;
}

void SphereJumpBank::release_samples_before(int sample) {
  const std::lock_guard lock(mutex_);
  banks_.erase(banks_.begin(), banks_.lower_bound({sample, 0u, 0}));
}

}  // namespace lucent::reference
