// test_paths.h: the checkout's and the build's folders and programs that the tests use. Only test_paths.cpp is
// compiled with their absolute paths, so the other test sources contain none and the compiler cache shares them
// between clones of the repository in different folders (cmake/compiler_cache.cmake).
#pragma once

namespace lucent::test {

const char* test_data_dir();  // tests/data
const char* source_dir();     // the checkout
const char* scenes_dir();     // scenes/
const char* cli_path();       // the `lucent` tool of this build
const char* test_out_dir();   // where GL tests write images for inspection (build/test-output)
const char* xvfb_run_path();  // xvfb-run, "" when the build found none

}  // namespace lucent::test

#define LUCENT_TEST_DATA (::lucent::test::test_data_dir())
#define LUCENT_SOURCE_DIR (::lucent::test::source_dir())
#define LUCENT_SCENES_DIR (::lucent::test::scenes_dir())
#define LUCENT_CLI (::lucent::test::cli_path())
#define LUCENT_TEST_OUT (::lucent::test::test_out_dir())
#define XVFB_RUN (::lucent::test::xvfb_run_path())
