#pragma once
// Runs the built `inbetween` tool (INBETWEEN_CLI) from a test: standard input from a string,
// standard output and standard error captured separately, and the exit code.  Every test gets its
// own scratch folder (test name + process id), because ctest runs the cases in parallel.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define INBETWEEN_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INBETWEEN_TEST_UNDER_ASAN 1
#endif
#endif

namespace inbetween::test {

/// True in a build with AddressSanitizer (GCC says so with __SANITIZE_ADDRESS__, clang with
/// __has_feature): its quarantine of freed memory makes peak-memory figures meaningless.
#if defined(INBETWEEN_TEST_UNDER_ASAN)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

/// What one run of the tool gave.
struct CliRun {
  int exit_code = -1;
  std::string out;  ///< standard output
  std::string err;  ///< standard error
};

/// The whole content of a file ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// This test's scratch folder, created on first use.
inline std::filesystem::path test_dir() {
  namespace fs = std::filesystem;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "none";
  for (char& c : name)
    if (c == '/' || c == '<' || c == '>') c = '_';
  const fs::path dir = fs::path(INBETWEEN_BINARY_DIR) / "cli-test" / (name + "-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

/// Writes `content` to `name` in this test's scratch folder and returns its path.
inline std::filesystem::path write_test_file(const std::string& name, const std::string& content) {
  const auto p = test_dir() / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

/// Runs `inbetween <args>` with `input` on standard input.
inline CliRun run_cli(const std::string& args, const std::string& input = "") {
  const auto dir = test_dir();
  const auto in = dir / "stdin.txt", out = dir / "stdout.txt", err = dir / "stderr.txt";
  std::ofstream(in, std::ios::binary) << input;
  // INBETWEEN_TEST_CLI runs the tests against another build of the tool (an older one, to see a
  // regression test fail before its fix).
  const char* cli = std::getenv("INBETWEEN_TEST_CLI");
  const std::string command = std::string("'") + (cli && *cli ? cli : INBETWEEN_CLI) + "' " + args + " < '" + in.string() + "' > '" +
                              out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// Peak resident memory (KiB, the child's own rusage from wait4) of one run of the tool with
/// standard output to /dev/null.
inline long peak_rss_kib(const std::vector<std::string>& args, int& exit_code) {
  std::vector<char*> argv;
  const char* other = std::getenv("INBETWEEN_TEST_CLI");
  std::string cli = other && *other ? other : INBETWEEN_CLI;
  argv.push_back(cli.data());
  std::vector<std::string> copy = args;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, cli.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  exit_code = -1;
  if (spawned != 0) return -1;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return -1;
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return usage.ru_maxrss;
}

}  // namespace inbetween::test
