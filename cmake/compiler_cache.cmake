# Compiles through ccache when it is installed (scripts/install-deps.sh installs it), so that a rebuild of unchanged
# sources, in any build tree of the same compiler and flags, is a cache lookup. A machine without ccache builds
# as before. LUCENT_CCACHE=OFF, or a launcher given on the command line, leaves the compiler alone.
#
# The settings travel in the launcher's environment rather than in a user's ccache.conf:
# - sloppiness include_file_mtime,include_file_ctime: a fresh clone's headers are seconds old when its build
#   starts, which ccache otherwise takes for files still being written and neither caches nor hits;
# - base_dir: the checkout's path is rewritten to a relative one, so a fresh clone in another folder hits the
#   entries that an earlier clone wrote;
# - hash_dir false: the build folder is not part of the key, so the sanitizer tree's line tables (-g) do not
#   keep a fresh clone from hitting; a hit's debug information names the folder of the clone that compiled it;
# - -fmacro-prefix-map (every build, with or without ccache): __FILE__, which GoogleTest's assertions expand, is
#   the path from the checkout's root, so a unity batch's preprocessed text is the same in every clone;
# - max_size 2G: both configurations of .ci/run with their sanitizer and fuzzing flags fit about five times.
option(LUCENT_CCACHE "Compile through ccache when it is installed" ON)
if(LUCENT_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(LUCENT_CCACHE_PROGRAM ccache)
  if(LUCENT_CCACHE_PROGRAM)
    set(lucent_ccache_launcher
        "${CMAKE_COMMAND}" -E env
        "CCACHE_SLOPPINESS=include_file_mtime,include_file_ctime"
        "CCACHE_BASEDIR=${CMAKE_SOURCE_DIR}"
        "CCACHE_NOHASHDIR=1"
        "CCACHE_MAXSIZE=2G"
        "${LUCENT_CCACHE_PROGRAM}")
    set(CMAKE_C_COMPILER_LAUNCHER ${lucent_ccache_launcher})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${lucent_ccache_launcher})
    message(STATUS "lucent: compiling through ${LUCENT_CCACHE_PROGRAM}")
  endif()
endif()
add_compile_options("-fmacro-prefix-map=${CMAKE_SOURCE_DIR}/=")
