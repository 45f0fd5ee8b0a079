// Shared by the suites that run the saagen CLI as a whole process: a scratch directory per test
// and a runner that captures the exit code, stdout and stderr.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace saagen::test {

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

// Single-quotes a shell word.
inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// A test with its own scratch directory (removed afterwards) that runs `saagen ARGS...`.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    scratch_ = std::filesystem::temp_directory_path() /
               (std::string("saagen-") + info->test_suite_name() + "-" + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(scratch_);
    std::filesystem::create_directories(scratch_);
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::permissions(scratch_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ignored);
    std::filesystem::remove_all(scratch_, ignored);
  }

  CliRun saagen(const std::vector<std::string>& arguments) const {
    std::string command = shell_quote(SAAGEN_CLI_PATH);
    // append() rather than operator+: GCC 12 reports a spurious -Wrestrict on the latter.
    for (const std::string& argument : arguments) command.append(" ").append(shell_quote(argument));
    return run_captured(command);
  }

  // Runs a shell command line (/bin/sh, as std::system does) with its stdout and stderr captured.
  CliRun run_captured(std::string command) const {
    const std::filesystem::path out = scratch_ / "stdout.txt", err = scratch_ / "stderr.txt";
    command.append(" >").append(shell_quote(out.string())).append(" 2>").append(shell_quote(err.string()));
    const int status = std::system(command.c_str());
    CliRun run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = read_text(out);
    run.err = read_text(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return run;
  }

  std::filesystem::path scratch_;
};

}  // namespace saagen::test
