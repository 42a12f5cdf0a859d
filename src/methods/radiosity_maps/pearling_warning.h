// pearling_warning.h: Dal Corso et al., Section 5: when the scattering length 1/sigma_tr is under about two
// light-map texels the contributions cluster ("pearling"). The warning names the light-map size that avoids it, or,
// when even the largest allowed size does not, says so with the texel size that largest size gives. No GL.
#pragma once
#include <cmath>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace lucent::methods {

// Empty when `length_mm` spans two texels of `texel_mm` (the light map at `light_map_size` texels a side); else
// the line to print. The texel size is inversely proportional to the light-map size.
inline std::string pearling_warning(std::string_view object, double length_mm, double texel_mm, int light_map_size,
                                    int max_light_map_size) {
  if (length_mm >= 2.0 * texel_mm) return {};
  const std::string head = fmt::format("{}: scattering length {:.3g} mm is under 2 light-map texels "
                                       "({:.3g} mm each); expect pearling",
                                       object, length_mm, texel_mm);
  const double needed = std::ceil(2.0 * texel_mm / length_mm * light_map_size);
  if (needed <= max_light_map_size) return fmt::format("{}, or raise method.light_map_size to {:.0f}", head, needed);
  return fmt::format("{}: method.light_map_size would have to be {:.3g}; its largest value, {}, gives {:.3g} mm texels",
                     head, needed, max_light_map_size, texel_mm * light_map_size / max_light_map_size);
}

}  // namespace lucent::methods
