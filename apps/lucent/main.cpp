// main.cpp: `lucent`: render scenes, evaluate BSSRDF models at a point, list material presets.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <system_error>
#include <iostream>

#include "commands.h"
#include "interrupted.h"
#include "io/interruption.h"
#include "lucent/error.h"

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) makes write() fail with EFBIG, reported like a full disk, instead of killing the
  // process mid-write: outputs are written to temporaries and renamed, so the old file stays intact either way.
  std::signal(SIGXFSZ, SIG_IGN);
  // SIGINT, SIGTERM, SIGHUP: temporaries and lock files are removed before the process ends (a reference saves its
  // completed passes first).
  lucent::install_interruption_handlers();
  CLI::App app{"lucent: real-time translucent materials with physically based subsurface scattering"};
  app.require_subcommand(1);
  app.set_version_flag("--version", lucent::cli::version_text(), "print lucent's version and exit");
  lucent::cli::add_render_command(app);
  lucent::cli::add_bssrdf_command(app);
  lucent::cli::add_materials_command(app);
  lucent::cli::add_slab_command(app);
  lucent::cli::add_reference_command(app);
  lucent::cli::add_compare_command(app);
  lucent::cli::add_tonemap_command(app);
  lucent::cli::add_bench_command(app);
  lucent::cli::add_envmap_command(app);
  lucent::cli::add_view_command(app);
  lucent::cli::add_export_command(app);
  lucent::cli::add_methods_command(app);
  lucent::cli::add_atlas_command(app);
  lucent::cli::add_tissue_maps_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // A bad command line is one line naming the option, like every other input error.
    std::cerr << "lucent: " << e.what() << " (lucent --help lists the options)\n";
    return 1;
  } catch (const lucent::cli::Interrupted& e) {
    std::cerr << "lucent: " << e.what() << "\n";
    return 128 + e.signal();
  } catch (const lucent::Error& e) {
    std::cerr << "lucent: " << e.what() << "\n";
    return 1;
  } catch (const std::system_error& e) {
    // fmt::print to a closed or full standard output; any other system error speaks for itself.
    if (std::ferror(stdout)) std::cerr << "lucent: <stdout>: cannot write: " << e.code().message() << "\n";
    else std::cerr << "lucent: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "lucent: internal error: " << e.what() << "\n";
    return 2;
  }
  // What was printed (JSON, tables) is output too: a full disk or closed pipe behind stdout is an error.
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "lucent: <stdout>: cannot write: " << std::strerror(errno) << "\n";
    return 1;
  }
  return 0;
}
