// commands.h: the subcommands of the `lucent` tool.
#pragma once
#include <CLI/CLI.hpp>

namespace lucent::cli {

void add_render_command(CLI::App& app);
void add_bssrdf_command(CLI::App& app);
void add_materials_command(CLI::App& app);
void add_slab_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_tonemap_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_envmap_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_atlas_command(CLI::App& app);

}  // namespace lucent::cli
