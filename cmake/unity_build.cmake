# Unity builds for the targets whose sources share heavy header-only libraries (CLI11 in the command-line tool,
# GoogleTest in the tests, pybind11 in the Python module): their inline functions and template instances are
# compiled and optimized once per batch of 8 sources instead of once per source. The libraries stay per-source
# builds. Measured on the 2-core machine: docs/design.md, "Build and test time". LUCENT_UNITY=OFF compiles every
# source on its own (and checks that each one stands alone).
option(LUCENT_UNITY "Unity builds for the tool, the tests and the Python module" ON)

# lucent_unity_build(TARGET [ALONE source...]): ALONE names sources compiled on their own, those so heavy that a
# batch holding them would be the build's critical path.
function(lucent_unity_build target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "ALONE")
  if(NOT LUCENT_UNITY)
    return()
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  # GCC's -Wsubobject-linkage is meant for headers: a test fixture in a source's anonymous namespace, used by the
  # TEST_F classes of the same source, is flagged once that source is included into a batch.
  target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-subobject-linkage>)
  if(arg_ALONE)
    set_source_files_properties(${arg_ALONE} TARGET_DIRECTORY ${target} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
  endif()
endfunction()
