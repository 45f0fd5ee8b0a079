// The fixture of test_safety's sources (test_safety_*.cpp, one executable): `saagen` run as a
// whole process in a scratch directory, under a file-size limit (a full disk) or a hang guard, and
// the one-line error every refusal must be.
#pragma once

#include "support/cli_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace saagen::test {

class Safety : public saagen::test::CliTest {
 protected:
  void expect_one_line_error(const CliRun& run, const std::string& expected) const {
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }

  // Runs saagen with a per-file size limit of `kib` KiB, as a full disk would refuse the write.
  CliRun saagen_with_file_limit(int kib, const std::vector<std::string>& arguments) const {
    std::string command = "trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; exec " + shell_quote(SAAGEN_CLI_PATH);
    for (const std::string& argument : arguments) command.append(" ").append(shell_quote(argument));
    return run_shell(command);
  }

  CliRun run_shell(const std::string& command) const { return run_captured("bash -c " + shell_quote(command)); }

  // Every entry of a directory, hidden ones (temporaries) included.
  std::set<std::string> entries(const std::filesystem::path& directory) const {
    std::set<std::string> names;
    if (!std::filesystem::exists(directory)) return names;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) names.insert(entry.path().filename().string());
    return names;
  }

  void write(const std::filesystem::path& path, const std::string& text) const {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
  }

  // A run that must refuse its input before any long work (rendering, generation, reading a
  // stream that never ends). Two checks, neither a timing: the bench and report print progress
  // lines on stderr once they render, so expect_one_line_error's single line says nothing ran
  // first; and a run that hangs is killed (exit 137, so expect_one_line_error fails) after
  // kHangGuardSeconds, a liveness bound far beyond any machine's load, not a speed target.
  static constexpr int kHangGuardSeconds = 300;
  CliRun refused_first(const std::vector<std::string>& arguments) const {
    std::string command = "exec timeout -s KILL " + std::to_string(kHangGuardSeconds) + " " + shell_quote(SAAGEN_CLI_PATH);
    for (const std::string& argument : arguments) command.append(" ").append(shell_quote(argument));
    return run_shell(command);
  }

  static std::vector<std::string> small_dictionary(const std::filesystem::path& output) {
    return {"glints", "dictionary", "--count", "4", "--lods", "2", "--resolution", "4", "-o", output.string()};
  }
};

}  // namespace saagen::test
