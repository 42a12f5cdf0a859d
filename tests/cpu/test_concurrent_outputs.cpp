// test_concurrent_outputs.cpp: an output is written by one lucent process at a time (OutputLock), and a signal
// neither loses a reference's samples nor leaves temporaries or lock files behind (io/interruption.h).
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli_runner.h"
#include "io/interruption.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/output_file.h"
#include "../child_exit.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using lucent::test::run_cli;

fs::path concurrent_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / "lucent_concurrent_outputs" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string lock_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const lucent::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Files lucent leaves only while it runs: temporaries and lock files.
int leftovers_in(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    n += name.find(".lucent-tmp-") != std::string::npos || name.find(".lucent-lock") != std::string::npos;
  }
  return n;
}

std::string small_scene(const fs::path& path) {
  std::ofstream(path) << R"({"scale_mm": 10, "camera": {"eye": [0, 0, 5]}, "lights": [{"direction": [0, 0, -1]}],
    "objects": [{"shape": "sphere", "material": "Skin1"}], "render": {"width": 8, "height": 6}})";
  return path.string();
}

// One output, as the CLI's --output names it.
std::vector<lucent::OutputPath> outputs_at(const std::string& path) { return {{path, "--output", {}}}; }

int samples_of(const fs::path& metadata) {
  return nlohmann::json::parse(std::ifstream(metadata))["samples_per_pixel"].get<int>();
}

TEST(OutputLock, ASecondWriterFailsNamingTheFirstAndTheLockIsRemovedAfter) {
  const fs::path dir = concurrent_dir("library");
  const std::vector<lucent::OutputPath> outputs = {{(dir / "a.exr").string(), "--output", {".exr"}}};
  {
    const lucent::OutputLock first(outputs);
    EXPECT_EQ(leftovers_in(dir), 1);
    EXPECT_EQ(lock_error([&] { lucent::OutputLock second(outputs); }),
              "--output " + (dir / "a.exr").string() + ": is being written by another lucent process (pid " +
                  std::to_string(::getpid()) + "); wait until it ends");
    // Devices are never locked: two writers of /dev/null do not wait for each other.
    const lucent::OutputLock device(outputs_at("/dev/null"));
    EXPECT_EQ(lock_error([&] { lucent::OutputLock again(outputs_at("/dev/null")); }), "(no error)");
  }
  EXPECT_EQ(leftovers_in(dir), 0);
  EXPECT_EQ(lock_error([&] { lucent::OutputLock third(outputs); }), "(no error)");
}

// While another process holds the reference's lock (here the test itself), `reference` fails at once, also with
// --resume, and leaves the set as it was.
TEST(CliConcurrentOutputs, ReferenceRefusesAnOutputAnotherProcessIsWriting) {
  const fs::path dir = concurrent_dir("held");
  const std::string scene = small_scene(dir / "s.json"), ref = (dir / "r.exr").string();
  const std::string command = "reference " + scene + " --integrator bssrdf -q -o " + ref;
  ASSERT_EQ(run_cli(command + " --spp 16").exit_code, 0);
  {
    const lucent::OutputLock held(outputs_at(ref));
    for (const std::string extra : {" --spp 64 --resume", " --spp 4 --seed 2"}) {
      auto r = run_cli(command + extra);
      EXPECT_EQ(r.exit_code, 1) << extra;
      EXPECT_EQ(r.output, "lucent: --output " + ref + ": is being written by another lucent process (pid " +
                              std::to_string(::getpid()) + "); wait until it ends\n")
          << extra;
    }
    EXPECT_EQ(samples_of(dir / "r.meta.json"), 16);
  }
  ASSERT_EQ(run_cli(command + " --spp 64 --resume").exit_code, 0);
  EXPECT_EQ(samples_of(dir / "r.meta.json"), 80);
  EXPECT_EQ(leftovers_in(dir), 0);
}

// Three references with seeds 1, 2, 3 started at once on one output, and three resumes of a 16-spp reference: each
// run either writes the whole set or fails with the lock's message, so the set on disk is one run's (its mean is the
// mean of the seed its metadata names) and the resumed sample count counts every success once.
TEST(CliConcurrentOutputs, ConcurrentWritersNeverMixASet) {
  const fs::path dir = concurrent_dir("concurrent");
  const std::string scene = small_scene(dir / "s.json"), ref = (dir / "r.exr").string();
  const std::string lucent = LUCENT_CLI;
  auto run_three = [&](const std::string& arguments) {  // arguments with {} for the run's number
    std::string shell;
    for (int k = 1; k <= 3; ++k)
      shell += lucent + " " + std::regex_replace(arguments, std::regex("\\{\\}"), std::to_string(k)) + " > " +
               (dir / ("out" + std::to_string(k) + ".txt")).string() + " 2>&1; echo $? > " +
               (dir / ("rc" + std::to_string(k) + ".txt")).string() + " &\n";
    EXPECT_EQ(std::system(("sh -c '" + shell + "wait'").c_str()), 0);
    int succeeded = 0;
    for (int k = 1; k <= 3; ++k) {
      std::ifstream rc(dir / ("rc" + std::to_string(k) + ".txt"));
      int code = -1;
      rc >> code;
      std::stringstream out;
      out << std::ifstream(dir / ("out" + std::to_string(k) + ".txt")).rdbuf();
      if (code == 0) ++succeeded;
      else EXPECT_NE(out.str().find("is being written by another lucent process"), std::string::npos) << out.str();
    }
    return succeeded;
  };
  const std::string base = "reference " + scene + " --integrator bssrdf -q ";
  run_three(base + "--spp 32 --seed {} -o " + ref);
  const int seed = nlohmann::json::parse(std::ifstream(dir / "r.meta.json"))["seed"].get<int>();
  const std::string alone = (dir / "alone.exr").string();
  ASSERT_EQ(run_cli(base + "--spp 32 --seed " + std::to_string(seed) + " -o " + alone).exit_code, 0);
  EXPECT_EQ(lucent::read_exr(ref).pixels, lucent::read_exr(alone).pixels) << "the mean is seed " << seed << "'s";
  EXPECT_EQ(lucent::read_exr((dir / "r.stderr.exr").string()).pixels,
            lucent::read_exr((dir / "alone.stderr.exr").string()).pixels);

  ASSERT_EQ(run_cli(base + "--spp 16 -o " + ref).exit_code, 0);
  const int succeeded = run_three(base + "--spp 64 --resume -o " + ref);
  EXPECT_GE(succeeded, 1);
  EXPECT_EQ(samples_of(dir / "r.meta.json"), 16 + 64 * succeeded);
  EXPECT_EQ(leftovers_in(dir), 0);
}

// The CLI's signal handling in a child process: `body` runs after install_interruption_handlers(); the result is
// how the child ended (exit code, or the signal that ended it).
struct ChildEnd {
  bool signalled = false;
  int code = 0;  // exit code or signal number
};

ChildEnd in_child(const std::function<void()>& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    lucent::install_interruption_handlers();
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return {true, WTERMSIG(status)};
  return {false, WEXITSTATUS(status)};
}

TEST(Interruption, ASignalRemovesRegisteredFilesAndEndsTheProcessAsItsDefault) {
  const fs::path dir = concurrent_dir("signal");
  const std::string temporary = (dir / ".a.exr.lucent-tmp-1-0").string(), kept = (dir / "kept.txt").string();
  std::ofstream(kept) << "not registered";
  ChildEnd end = in_child([&] {
    std::ofstream(temporary) << "half written";
    const lucent::RemoveOnSignal removal(temporary);
    const lucent::OutputLock lock(outputs_at((dir / "a.exr").string()));
    ::raise(SIGTERM);
    ::_exit(3);  // not reached
  });
  EXPECT_TRUE(end.signalled);
  EXPECT_EQ(end.code, SIGTERM);
  EXPECT_EQ(leftovers_in(dir), 0) << "the temporary and the lock file are removed";
  EXPECT_TRUE(fs::exists(kept));
}

TEST(Interruption, ADeferredSignalIsReportedOrEndsTheProcessAfterTheSection) {
  // Taken: the process goes on and ends its own way.
  ChildEnd taken = in_child([] {
    lucent::DeferredInterruption deferred;
    ::raise(SIGINT);
    if (deferred.received() != SIGINT) ::_exit(10);
    ::_exit(deferred.take() == SIGINT ? 7 : 11);
  });
  EXPECT_FALSE(taken.signalled);
  EXPECT_EQ(taken.code, 7);
  // Not taken: the section runs to its end, then the signal ends the process.
  const fs::path dir = concurrent_dir("deferred");
  ChildEnd deferred_end = in_child([&] {
    {
      const lucent::DeferredInterruption section;
      ::raise(SIGTERM);
      std::ofstream(dir / "after_signal.txt") << "the section went on";
    }
    ::_exit(5);  // not reached
  });
  EXPECT_TRUE(deferred_end.signalled);
  EXPECT_EQ(deferred_end.code, SIGTERM);
  EXPECT_TRUE(fs::exists(dir / "after_signal.txt"));
}

// SIGINT during a long reference: the completed passes are saved (an honest mean of a uniform sample count, equal to
// an uninterrupted reference of that many samples), the command says how many and how to resume, and exits 130.
TEST(CliConcurrentOutputs, InterruptedReferenceSavesItsCompletedPasses) {
  const fs::path dir = concurrent_dir("interrupted");
  const std::string scene = small_scene(dir / "s.json"), ref = (dir / "r.exr").string();
  const std::string log = (dir / "log.txt").string();
  std::vector<std::string> args = {LUCENT_CLI, "reference", scene, "--integrator", "bssrdf", "--spp", "1000000000",
                                   "-q", "-o", ref};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Wait until the child has rendered for a while: half a second of its own CPU time (utime in /proc/<pid>/stat).
  for (int tries = 0; tries < 600; ++tries) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
    std::istringstream fields(text.substr(text.rfind(')') + 2));
    std::string field;
    long utime = 0;
    for (int k = 3; k <= 14 && fields >> field; ++k)
      if (k == 14) utime = std::stol(field);
    if (utime >= ::sysconf(_SC_CLK_TCK) / 2) break;
    ::usleep(100000);
  }
  ::kill(pid, SIGINT);
  // A reference that does not stop is ended after two minutes, and the test fails below (not a timing check: it
  // keeps a broken build from hanging the test run).
  const int status = lucent::test::wait_for_exit_or_kill(pid);
  std::stringstream output;
  output << std::ifstream(log).rdbuf();
  ASSERT_TRUE(WIFEXITED(status)) << output.str();
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT);
  std::smatch m;
  const std::string text = output.str();
  ASSERT_TRUE(std::regex_match(text, m, std::regex(
      "lucent: interrupted by SIGINT: saved ([0-9]+) of the 1000000000 samples per pixel asked \\(([0-9]+) in all\\) in "
      ".*r\\.exr; to add the other ([0-9]+), run the same command with --resume --spp ([0-9]+)\n")))
      << text;
  const int saved = std::stoi(m[1].str());
  EXPECT_EQ(std::stoi(m[2].str()), saved);
  EXPECT_EQ(std::stoi(m[3].str()), 1000000000 - saved);
  EXPECT_EQ(samples_of(dir / "r.meta.json"), saved);
  EXPECT_EQ(leftovers_in(dir), 0);
  // The same samples rendered without interruption: the same mean and standard error (float rounding apart).
  const std::string whole = (dir / "whole.exr").string();
  ASSERT_EQ(run_cli("reference " + scene + " --integrator bssrdf -q --spp " + std::to_string(saved) + " -o " + whole)
                .exit_code,
            0);
  for (const auto& [a, b] : {std::pair{ref, whole}, std::pair{(dir / "r.stderr.exr").string(),
                                                               (dir / "whole.stderr.exr").string()}}) {
    const lucent::ImageRGBA32F x = lucent::read_exr(a), y = lucent::read_exr(b);
    ASSERT_EQ(x.pixels.size(), y.pixels.size());
    for (std::size_t i = 0; i < x.pixels.size(); ++i)
      EXPECT_NEAR(x.pixels[i], y.pixels[i], 1e-5f * std::max(1.0f, std::abs(y.pixels[i]))) << a << " value " << i;
  }
  // And it resumes.
  ASSERT_EQ(run_cli("reference " + scene + " --integrator bssrdf -q --spp 3 --resume -o " + ref).exit_code, 0);
  EXPECT_EQ(samples_of(dir / "r.meta.json"), saved + 3);
}

}  // namespace
