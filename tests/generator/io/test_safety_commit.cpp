// All-or-nothing commits (test_safety): a set of outputs is either wholly replaced or left
// exactly as it was -- an immutable file, another user's file in a sticky directory, a rename that
// fails half-way, a signal between renames or while staging.
#include "safety_support.hpp"

#include "saagen/error.hpp"
#include "saagen/io/output.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

using saagen::test::CliRun;
using saagen::test::read_text;
using saagen::test::Safety;
using saagen::test::shell_quote;

// ---------------------------------------------------------------------------------------------
// All-or-nothing commits: a set of outputs is either wholly replaced or left exactly as it was.

// Every file of a directory, hidden ones (temporaries, backups) included, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& directory) {
  std::map<std::string, std::string> files;
  if (!fs::exists(directory)) return files;
  for (const auto& entry : fs::directory_iterator(directory)) files[entry.path().filename().string()] = read_text(entry.path());
  return files;
}

// The files a run reports as written, in the order it commits them.
std::vector<std::string> written_paths(const std::string& out) {
  std::vector<std::string> paths;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("wrote     ", 0) == 0) paths.push_back(line.substr(10));
  }
  return paths;
}

// Sets or clears the immutable flag (chattr +i / -i); false where the process lacks
// CAP_LINUX_IMMUTABLE or the file system has no such flag.
bool set_immutable(const fs::path& path, bool on) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  int flags = 0;
  bool done = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
  flags = on ? flags | FS_IMMUTABLE_FL : flags & ~FS_IMMUTABLE_FL;
  done = done && ::ioctl(fd, FS_IOC_SETFLAGS, &flags) == 0;
  ::close(fd);
  return done;
}

// Clears the immutable flag of the files it was given when the test ends, failed or not (the
// scratch directory could not be removed otherwise).
class ImmutableFiles {
 public:
  bool add(const fs::path& path) {
    if (!set_immutable(path, true)) return false;
    paths_.push_back(path);
    return true;
  }
  ~ImmutableFiles() {
    for (const fs::path& path : paths_) set_immutable(path, false);
  }

 private:
  std::vector<fs::path> paths_;
};

TEST_F(Safety, AnImmutableFileLeavesTheWholeSetUnchanged) {
  const fs::path out = scratch_ / "out", passes = scratch_ / "pass", glints = scratch_ / "g";
  const CliRun first = saagen({"emit", "-o", out.string(), "--sigma2", "0.5"});
  const CliRun first_pass = saagen({"pass", "-v", "deferred-avg", "-o", passes.string(), "--sigma2", "0.5"});
  auto dictionary = small_dictionary(glints / "d.ktx2");
  dictionary.insert(dictionary.end(), {"--raw", (glints / "d.f32").string()});
  ASSERT_EQ(saagen(dictionary).exit_code, 0);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(first_pass.exit_code, 0) << first_pass.err;
  // The last file each run commits: under a rename-as-you-go commit, every other file would be new.
  const fs::path emit_victim = written_paths(first.out).back(), pass_victim = passes / "saa_pass_deferred_avg.h";
  ASSERT_TRUE(fs::exists(pass_victim));
  ImmutableFiles immutable;
  if (!immutable.add(emit_victim)) GTEST_SKIP() << "chattr +i is refused here (no CAP_LINUX_IMMUTABLE, or the file system has no flag)";
  ASSERT_TRUE(immutable.add(pass_victim));
  ASSERT_TRUE(immutable.add(glints / "d.f32"));
  const auto emit_before = snapshot(out), pass_before = snapshot(passes), glints_before = snapshot(glints);

  const CliRun emit = saagen({"emit", "-o", out.string()});
  expect_one_line_error(emit, emit_victim.string() + ": cannot be replaced (Operation not permitted: the file is immutable");
  EXPECT_NE(emit.err.find("nothing was changed"), std::string::npos) << emit.err;
  EXPECT_EQ(snapshot(out), emit_before);
  // The pass's header embeds the SPIR-V: neither may be new without the other.
  const CliRun pass = saagen({"pass", "-v", "deferred-avg", "-o", passes.string()});
  expect_one_line_error(pass, pass_victim.string() + ": cannot be replaced");
  EXPECT_EQ(snapshot(passes), pass_before);
  dictionary[3] = "8";  // --count 8: every file of the dictionary changes
  expect_one_line_error(saagen(dictionary), (glints / "d.f32").string() + ": cannot be replaced");
  EXPECT_EQ(snapshot(glints), glints_before);
}

// Another user's file in a sticky directory (as in /tmp) cannot be renamed over: the run (as
// user nobody) is refused before any file of the set is replaced.
TEST_F(Safety, AnotherUsersFileInAStickyDirectoryLeavesTheWholeSetUnchanged) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to run saagen as another user (setpriv) and to own a file there";
  if (std::system("command -v setpriv >/dev/null 2>&1") != 0) GTEST_SKIP() << "setpriv (util-linux) is not installed";
  const fs::path sticky = scratch_ / "sticky";
  fs::create_directories(sticky);
  fs::permissions(scratch_, fs::perms::all, fs::perm_options::add);
  fs::permissions(sticky, fs::perms::all | fs::perms::sticky_bit);
  const std::string as_nobody = "setpriv --reuid=65534 --regid=65534 --clear-groups " + shell_quote(SAAGEN_CLI_PATH);
  const CliRun first = run_shell(as_nobody + " emit -o " + shell_quote(sticky.string()) + " --sigma2 0.5");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  // The last file committed becomes root's (same bytes, writable by all: only the sticky rule stops a rename over it).
  const fs::path victim = written_paths(first.out).back();
  const std::string bytes = read_text(victim);
  fs::remove(victim);
  write(victim, bytes);
  fs::permissions(victim, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::group_write |
                              fs::perms::others_read | fs::perms::others_write);
  const auto before = snapshot(sticky);

  const CliRun run = run_shell(as_nobody + " emit -o " + shell_quote(sticky.string()));
  expect_one_line_error(run, victim.string() + ": cannot be replaced (Operation not permitted: another user's file in a sticky directory)");
  EXPECT_NE(run.err.find("nothing was changed"), std::string::npos) << run.err;
  EXPECT_EQ(snapshot(sticky), before);
}

// The commit hook of these tests: what to do after which step.
struct HookAction {
  saagen::CommitStep step = saagen::CommitStep::renamed;
  std::size_t index = 0;
  std::function<void()> action;
};
HookAction hook_action;

void run_hook_action(saagen::CommitStep step, std::size_t index) {
  if (hook_action.action && step == hook_action.step && index == hook_action.index) hook_action.action();
}

class Commit : public saagen::test::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    saagen::set_commit_hook(&run_hook_action);
    old_ = {{dir() / "a.txt", "saagen-output: a, old\n"}, {dir() / "b.txt", "saagen-output: b, old\n"}};
    saagen::write_outputs(old_, false);
  }
  void TearDown() override {
    saagen::set_commit_hook(nullptr);
    hook_action = {};
    CliTest::TearDown();
  }
  fs::path dir() const { return scratch_ / "d"; }
  // A new file in directories that do not exist yet, then new bytes for a.txt and b.txt.
  std::vector<saagen::OutputFile> new_set() const {
    return {{dir() / "new" / "deeper" / "c.txt", "saagen-output: c, new\n"},
            {dir() / "a.txt", "saagen-output: a, new\n"},
            {dir() / "b.txt", "saagen-output: b, new\n"}};
  }
  // Runs write_outputs(new_set()) in a child process; its wait status.
  int status_of_child_commit() const {
    const pid_t child = ::fork();
    if (child == 0) {
      const struct rlimit no_core {};
      ::setrlimit(RLIMIT_CORE, &no_core);  // SIGXFSZ's default action dumps core
      try {
        saagen::write_outputs(new_set(), false);
      } catch (...) {
        ::_exit(2);
      }
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return status;
  }
  std::vector<saagen::OutputFile> old_;
};

// A rename that fails after others succeeded (here b.txt became a directory meanwhile) puts back
// the files already replaced (the same inodes), removes the new file and the directories the run
// created, and leaves no temporary or backup.
TEST_F(Commit, AFailedRenamePutsBackEveryFileAndRemovesNewDirectories) {
  struct stat a_before {};
  ASSERT_EQ(::stat((dir() / "a.txt").c_str(), &a_before), 0);
  hook_action = {saagen::CommitStep::renamed, 1, [&] {
                   fs::rename(dir() / "b.txt", dir() / "b.moved");
                   fs::create_directories(dir() / "b.txt" / "inside");
                 }};
  try {
    saagen::write_outputs(new_set(), false);
    ADD_FAILURE() << "the commit succeeded";
  } catch (const saagen::Error& error) {
    EXPECT_EQ(std::string(error.what()), (dir() / "b.txt").string() + ": cannot be replaced (Is a directory); nothing was changed");
  }
  EXPECT_EQ(read_text(dir() / "a.txt"), "saagen-output: a, old\n");
  struct stat a_after {};
  ASSERT_EQ(::stat((dir() / "a.txt").c_str(), &a_after), 0);
  EXPECT_EQ(a_after.st_ino, a_before.st_ino);
  EXPECT_EQ(snapshot(dir()), (std::map<std::string, std::string>{
                                 {"a.txt", "saagen-output: a, old\n"}, {"b.moved", "saagen-output: b, old\n"}, {"b.txt", ""}}));
  EXPECT_FALSE(fs::exists(dir() / "new"));
}

// SIGTERM (or Ctrl-C) arriving between two renames waits until the set is whole: the process
// then ends by the signal, with every file new and no temporary or backup left.
TEST_F(Commit, ASignalBetweenRenamesActsOnceTheSetIsWhole) {
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    hook_action = {};
    saagen::write_outputs(old_, true);
    fs::remove_all(dir() / "new");
    hook_action = {saagen::CommitStep::renamed, 0, [signal] { ::raise(signal); }};
    const int status = status_of_child_commit();
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "signal " << signal << ", status " << status;
    EXPECT_EQ(snapshot(dir()), (std::map<std::string, std::string>{
                                   {"a.txt", "saagen-output: a, new\n"}, {"b.txt", "saagen-output: b, new\n"}, {"new", ""}}));
    EXPECT_EQ(snapshot(dir() / "new" / "deeper"), (std::map<std::string, std::string>{{"c.txt", "saagen-output: c, new\n"}}));
  }
}

// SIGINT, SIGTERM or SIGXFSZ while the set is staged: no file is replaced, the temporaries and
// the directories the run created are removed.
TEST_F(Commit, ASignalWhileStagingRemovesTemporariesAndNewDirectories) {
  for (const int signal : {SIGINT, SIGTERM, SIGXFSZ}) {
    hook_action = {saagen::CommitStep::staged, 1, [signal] { ::raise(signal); }};
    const int status = status_of_child_commit();
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "signal " << signal << ", status " << status;
    EXPECT_EQ(snapshot(dir()),
              (std::map<std::string, std::string>{{"a.txt", "saagen-output: a, old\n"}, {"b.txt", "saagen-output: b, old\n"}}));
  }
}

// The file-size limit's SIGXFSZ through the command line, into a directory that did not exist.
TEST_F(Safety, AFileSizeSignalRemovesTheDirectoriesTheRunCreated) {
  const std::string command =
      "ulimit -f 8; exec " + shell_quote(SAAGEN_CLI_PATH) + " emit -o " + shell_quote((scratch_ / "new" / "deeper").string());
  const CliRun run = run_shell(command);
  EXPECT_EQ(run.exit_code, 128 + SIGXFSZ) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "new"));
}

}  // namespace
