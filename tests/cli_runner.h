// cli_runner.h: runs the `lucent` tool (LUCENT_CLI) with arguments and returns its exit code and output.
#pragma once
#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>
#include "test_paths.h"

namespace lucent::test {

struct CliResult {
  int exit_code;
  std::string output;  // stdout and stderr
};

inline CliResult run_cli(const std::string& arguments, const std::string& environment = "") {
  std::string command = environment + " " + LUCENT_CLI + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer;
  while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace lucent::test
