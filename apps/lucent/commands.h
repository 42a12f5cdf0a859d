// commands.h: the subcommands of the `lucent` tool.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "cache/precompute_cache.h"

namespace lucent::cli {

// "lucent 0.1.0 (git v0.1-12-gabc1234)": project()'s version and the source tree's `git describe` when built from
// a checkout (both recorded when CMake configured the build).
std::string version_text();

void add_render_command(CLI::App& app);
void add_bssrdf_command(CLI::App& app);
void add_materials_command(CLI::App& app);
void add_materials_invert_command(CLI::App& materials);  // `lucent materials invert`
void add_slab_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_tonemap_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_envmap_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_methods_command(CLI::App& app);
void add_atlas_command(CLI::App& app);
void add_tissue_maps_command(CLI::App& app);

// --no-cache, on the commands that may precompute: the precompute cache is neither read nor written.
inline void add_no_cache_flag(CLI::App* cmd) {
  cmd->add_flag_callback("--no-cache", [] { cache::set_enabled(false); },
                         "neither read nor write the precompute cache ($LUCENT_CACHE_DIR, $XDG_CACHE_HOME/lucent or "
                         "~/.cache/lucent)");
}

}  // namespace lucent::cli
