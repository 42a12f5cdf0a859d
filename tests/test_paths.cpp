// test_paths.cpp: the paths of test_paths.h, from the build's definitions of LUCENT_TEST_PATH_* (tests/CMakeLists.txt).
#include "test_paths.h"

namespace lucent::test {

const char* test_data_dir() { return LUCENT_TEST_PATH_DATA; }
const char* source_dir() { return LUCENT_TEST_PATH_SOURCE; }
const char* scenes_dir() { return LUCENT_TEST_PATH_SCENES; }
const char* cli_path() { return LUCENT_TEST_PATH_CLI; }
const char* test_out_dir() { return LUCENT_TEST_PATH_OUT; }
const char* xvfb_run_path() { return LUCENT_TEST_PATH_XVFB_RUN; }

}  // namespace lucent::test
