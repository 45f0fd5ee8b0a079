#include "saagen/io/output.hpp"

#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/ktx2.hpp"
#include "saagen/io/marker.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <system_error>

#include <fcntl.h>
#include <linux/fs.h>
#include <pthread.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace saagen {
namespace {

namespace fs = std::filesystem;

// Existing outputs larger than this are never read back: they are foreign unless forced.
constexpr std::size_t existing_read_limit = std::size_t{512} << 20;

std::string error_text(int error) { return std::generic_category().message(error); }

// What lies at an output path, inspected without following a link there.
struct Existing {
  bool exists = false;
  bool link = false;
  bool too_large = false;
  std::string bytes;
};

std::string read_descriptor(int fd, const fs::path& path) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t count = ::read(fd, buffer, sizeof buffer);
    if (count < 0 && errno == EINTR) continue;
    if (count < 0) throw Error(fmt::format("{}: cannot be read ({}); check its permissions", path.string(), error_text(errno)));
    if (count == 0) return bytes;
    bytes.append(buffer, static_cast<std::size_t>(count));
  }
}

Existing inspect(const fs::path& path) {
  Existing existing;
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return existing;
    throw Error(fmt::format("{}: cannot be inspected ({}); check the directory's permissions", path.string(), error_text(errno)));
  }
  existing.exists = true;
  if (S_ISLNK(status.st_mode)) {
    existing.link = true;
    return existing;
  }
  if (S_ISDIR(status.st_mode)) {
    throw Error(fmt::format("{}: is a directory; remove it or choose another output path", path.string()));
  }
  if (!S_ISREG(status.st_mode)) {
    throw Error(fmt::format("{}: exists and is not a regular file; remove it or choose another output path", path.string()));
  }
  if (static_cast<std::size_t>(status.st_size) > existing_read_limit) {
    existing.too_large = true;
    return existing;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(fmt::format("{}: cannot be read ({}); check its permissions", path.string(), error_text(errno)));
  try {
    existing.bytes = read_descriptor(fd, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return existing;
}

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

std::string sidecar_fingerprint(std::string_view bytes) { return fmt::format("bytes={} fnv1a64={:016x}", bytes.size(), fnv1a64(bytes)); }

fs::path sidecar_path(const fs::path& path) { return fs::path(path.string() + ".saagen"); }

std::string_view ktx2_identifier() { return {"\xABKTX 20\xBB\r\n\x1A\n", 12}; }
std::string_view png_signature() { return {"\x89PNG\r\n\x1A\n", 8}; }

// A KTX2 file that parses and carries one of the key/value entries saagen writes.
bool ktx2_written_by_saagen(std::string_view bytes) {
  static const std::set<std::string, std::less<>> keys = {"saagen.glints", "saagen.lean", "saagen.prefilter", "saagen.marker"};
  try {
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    const Ktx2Image image = read_ktx2(std::span<const std::uint8_t>(data, bytes.size()));
    return std::any_of(image.key_values.begin(), image.key_values.end(), [](const auto& entry) { return keys.count(entry.first) != 0; });
  } catch (const Error&) {
    return false;
  }
}

std::uint32_t big_endian32(std::string_view bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t index = 0; index < 4; ++index) value = value << 8 | static_cast<unsigned char>(bytes[at + index]);
  return value;
}

// A PNG whose chunks before the image data hold saagen's tEXt chunk: keyword "Software", text
// starting with the output tag (report/src/report.cpp writes it right after IHDR).
bool png_written_by_saagen(std::string_view bytes) {
  const std::string prefix = std::string("Software") + '\0' + std::string(output_tag);
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::uint32_t length = big_endian32(bytes, at);
    if (length > bytes.size() - at - 12) return false;
    const std::string_view type = bytes.substr(at + 4, 4);
    if (type == "IDAT" || type == "IEND") return false;
    if (type == "tEXt" && bytes.substr(at + 8, length).substr(0, prefix.size()) == prefix) return true;
    at += 12 + std::size_t{length};
  }
  return false;
}

bool is_spirv(std::string_view bytes) {
  return bytes.size() >= 20 && bytes.size() % 4 == 0 && bytes.substr(0, 4) == std::string_view("\x03\x02\x23\x07", 4);
}

// A little-endian SPIR-V module with an OpSourceExtension or OpModuleProcessed instruction whose
// string is saagen's tag: the output tag (`compile`) or an emission marker line (libraries, passes).
bool spirv_written_by_saagen(std::string_view bytes) {
  constexpr std::uint32_t op_source_extension = 4, op_module_processed = 330, op_function = 54;
  const auto word = [&](std::size_t index) {
    std::uint32_t value = 0;
    for (std::size_t byte = 0; byte < 4; ++byte) value |= std::uint32_t(static_cast<unsigned char>(bytes[index * 4 + byte])) << (8 * byte);
    return value;
  };
  const std::size_t words = bytes.size() / 4;
  for (std::size_t index = 5; index < words;) {
    const std::uint32_t length = word(index) >> 16, opcode = word(index) & 0xffffu;
    if (length == 0 || length > words - index || opcode == op_function) return false;
    if (opcode == op_source_extension || opcode == op_module_processed) {
      const std::string_view operand = bytes.substr((index + 1) * 4, (length - 1) * 4);
      const std::string_view text = operand.substr(0, operand.find('\0'));
      if (text.substr(0, output_tag.size()) == output_tag) return true;
      if (text.substr(0, 17) == "// saagen-marker:" && find_marker(text)) return true;
    }
    index += length;
  }
  return false;
}

bool is_json_object(std::string_view bytes) {
  const auto first = bytes.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && bytes[first] == '{';
}

// A JSON object whose top-level "generator" is the output tag naming a saagen command.
bool json_written_by_saagen(std::string_view bytes) {
  const nlohmann::json json = nlohmann::json::parse(bytes, nullptr, false);
  if (!json.is_object()) return false;
  const auto generator = json.find("generator");
  if (generator == json.end() || !generator->is_string()) return false;
  return generator->get_ref<const std::string&>().rfind(std::string(output_tag) + " saagen ", 0) == 0;
}

// The line at `at` (without its end of line) and where the next one starts.
std::string_view line_at(std::string_view bytes, std::size_t at, std::size_t* next) {
  if (at >= bytes.size()) {
    *next = bytes.size();
    return {};
  }
  auto end = bytes.find('\n', at);
  if (end == std::string_view::npos) end = bytes.size();
  *next = std::min(end + 1, bytes.size());
  std::string_view line = bytes.substr(at, end - at);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

// A text file that starts the way saagen starts it: the generated-by line, then a marker line
// that parses (emitted shaders, headers, passes); or the tag as the first line, bare (sidecars)
// or as a comment (Markdown, SVG; HTML after its doctype line).
bool text_written_by_saagen(std::string_view bytes) {
  std::size_t second = 0, third = 0;
  const std::string_view first_line = line_at(bytes, 0, &second);
  const std::string_view second_line = line_at(bytes, second, &third);
  if (first_line.rfind("// Generated by saagen ", 0) == 0) {
    return second_line.rfind("// saagen-marker:", 0) == 0 && find_marker(second_line).has_value();
  }
  const auto is_tag_line = [](std::string_view line) {
    if (line.substr(0, output_tag.size()) == output_tag) return line.size() > output_tag.size();
    const std::string opening = "<!-- " + std::string(output_tag) + " ";
    return line.rfind(opening, 0) == 0 && line.size() >= opening.size() + 4 && line.substr(line.size() - 4) == " -->";
  };
  if (is_tag_line(first_line)) return true;
  return first_line == "<!DOCTYPE html>" && is_tag_line(second_line);
}

bool sidecar_vouches_for(const fs::path& path, std::string_view bytes) {
  const Existing sidecar = inspect(sidecar_path(path));
  if (!sidecar.exists || sidecar.link || sidecar.too_large) return false;
  // Its own form: the tag line naming this file, then the fingerprint line.
  const std::string expected = fmt::format("{} sidecar of {}\n{}\n", output_tag, path.filename().string(), sidecar_fingerprint(bytes));
  return sidecar.bytes.rfind(expected, 0) == 0;
}

fs::path directory_of(const fs::path& path) { return path.has_parent_path() ? path.parent_path() : fs::path("."); }

// The directory exists and is writable, or its nearest existing ancestor is a writable directory.
void check_directory(const fs::path& directory) {
  fs::path existing = directory;
  struct stat status {};
  while (::stat(existing.c_str(), &status) != 0) {
    const int error = errno;
    const fs::path parent = existing.has_parent_path() ? existing.parent_path() : fs::path(".");
    if (error != ENOENT || parent == existing) {
      throw Error(
          fmt::format("{}: cannot create the output directory ({}); choose a writable path", directory.string(), error_text(error)));
    }
    existing = parent;
  }
  if (!S_ISDIR(status.st_mode)) {
    throw Error(fmt::format("{}: cannot create the output directory ({} is not a directory); choose a writable path", directory.string(),
                            existing.string()));
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    throw Error(fmt::format("{}: cannot write in this directory; choose a writable output path", existing.string()));
  }
}

// The identity of an existing file (device and inode), without following a link at `path`.
std::optional<std::pair<dev_t, ino_t>> identity(const fs::path& path, bool follow) {
  struct stat status {};
  if ((follow ? ::stat(path.c_str(), &status) : ::lstat(path.c_str(), &status)) != 0) return std::nullopt;
  return std::make_pair(status.st_dev, status.st_ino);
}

// Names are compared with their directory resolved (a linked directory names the same place) and
// existing files by identity (a hard link is the same file).
void check_named_once(const std::vector<fs::path>& paths) {
  std::set<fs::path> seen;
  std::set<std::pair<dev_t, ino_t>> seen_files;
  for (const fs::path& path : paths) {
    if (path.empty() || !path.has_filename()) throw Error(fmt::format("'{}': not a file name; pass an output path", path.string()));
    const fs::path absolute = fs::absolute(path).lexically_normal();
    std::error_code error;
    fs::path directory = fs::weakly_canonical(absolute.parent_path(), error);
    if (error) directory = absolute.parent_path();
    const auto file = identity(path, false);
    if (!seen.insert(directory / absolute.filename()).second || (file && !seen_files.insert(*file).second)) {
      throw Error(
          fmt::format("{}: would be written twice in one run (a repeated variant or name, or two names of one file); name each output once",
                      path.string()));
    }
  }
  // A file and a directory of the same run may not share a name (bench --json X --report X).
  for (const fs::path& name : seen) {
    for (fs::path parent = name.parent_path(); parent.has_relative_path(); parent = parent.parent_path()) {
      if (seen.count(parent)) {
        throw Error(fmt::format("{}: is both an output file and the directory of {} in one run; choose different paths", parent.string(),
                                name.string()));
      }
    }
  }
}

// No output is one of the command's inputs, whatever its name (not even with --force).
void check_not_inputs(const std::vector<fs::path>& paths, const std::vector<fs::path>& inputs) {
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    const auto read = identity(input, true);
    if (!read) continue;
    for (const fs::path& path : paths) {
      if (identity(path, false) == read) {
        throw Error(fmt::format("{}: is an input of this command ({}); choose another output path", path.string(), input.string()));
      }
    }
  }
}

// Whether the path must be written (false: it already holds exactly these bytes). Throws when the
// path may not be written.
bool needs_writing(const fs::path& path, const std::optional<std::string_view>& content, bool force) {
  check_directory(directory_of(path));
  const Existing existing = inspect(path);
  if (!existing.exists) return true;
  if (existing.link && !force) {
    throw Error(fmt::format(
        "{}: is a symbolic link; saagen never writes through one (remove it, or pass --force to replace the link itself)", path.string()));
  }
  if (existing.link) return true;
  if (content && !existing.too_large && existing.bytes == *content) return false;
  if (!force && (existing.too_large || !written_by_saagen(path, existing.bytes))) {
    throw Error(fmt::format("{}: exists and was not written by saagen; refusing to overwrite it (use --force)", path.string()));
  }
  return true;
}

mode_t creation_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

void write_all(int fd, std::string_view content, const fs::path& path) {
  while (!content.empty()) {
    const ssize_t count = ::write(fd, content.data(), content.size());
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) {
      const int error = count < 0 ? errno : ENOSPC;
      throw Error(fmt::format("{}: write failed ({}); free some space or choose another output path", path.string(), error_text(error)));
    }
    content.remove_prefix(static_cast<std::size_t>(count));
  }
}

// Temporaries that a signal ending the process (Ctrl-C, SIGTERM, SIGHUP, a file-size limit's
// SIGXFSZ) would leave behind: their names sit in fixed slots that the handler, which may only
// make async-signal-safe calls, unlinks before the signal takes its previous action. Handlers are
// installed while temporaries exist, and only for signals whose action is the default one (an
// ignored signal stays ignored: `trap '' XFSZ` still makes write() fail with EFBIG).
class SignalCleanup {
 public:
  static constexpr int signals[] = {SIGINT, SIGTERM, SIGHUP, SIGXFSZ};

  // Holds the handlers installed while alive (nested and concurrent holders share them).
  SignalCleanup() {
    const std::lock_guard lock(mutex_);
    if (holders_++ > 0) return;
    for (std::size_t index = 0; index < std::size(signals); ++index) {
      struct sigaction current {};
      installed_[index] = false;
      if (::sigaction(signals[index], nullptr, &current) != 0 || current.sa_handler != SIG_DFL || (current.sa_flags & SA_SIGINFO)) continue;
      struct sigaction action {};
      action.sa_handler = &SignalCleanup::handle;
      sigemptyset(&action.sa_mask);
      previous_[index] = current;
      installed_[index] = ::sigaction(signals[index], &action, nullptr) == 0;
    }
  }
  ~SignalCleanup() {
    const std::lock_guard lock(mutex_);
    if (--holders_ > 0) return;
    for (std::size_t index = 0; index < std::size(signals); ++index) {
      if (installed_[index]) ::sigaction(signals[index], &previous_[index], nullptr);
      installed_[index] = false;
    }
  }
  SignalCleanup(const SignalCleanup&) = delete;
  SignalCleanup& operator=(const SignalCleanup&) = delete;

  // A temporary's name (its storage outlives the registration); false when every slot is taken
  // (that temporary is then removed by the destructor alone).
  static bool add(const char* name) {
    for (auto& slot : slots_) {
      const char* empty = nullptr;
      if (slot.compare_exchange_strong(empty, name)) return true;
    }
    return false;
  }
  static void remove(const char* name) {
    for (auto& slot : slots_) {
      const char* expected = name;
      if (slot.compare_exchange_strong(expected, nullptr)) return;
    }
  }
  // A directory this run created, removed (while empty) by a signal after the temporaries.
  static bool add_directory(const char* name) {
    for (auto& slot : directory_slots_) {
      const char* empty = nullptr;
      if (slot.compare_exchange_strong(empty, name)) return true;
    }
    return false;
  }
  static void remove_directory(const char* name) {
    for (auto& slot : directory_slots_) {
      const char* expected = name;
      if (slot.compare_exchange_strong(expected, nullptr)) return;
    }
  }

  // The signals the handler takes, blocked in the calling thread while alive: a commit (backups,
  // renames, rollback) runs to its end, and a signal that arrived meanwhile acts afterwards. A
  // handler running in another thread waits for it.
  class Deferred {
   public:
    Deferred() {
      sigset_t set;
      sigemptyset(&set);
      for (const int signal : signals) sigaddset(&set, signal);
      ::pthread_sigmask(SIG_BLOCK, &set, &previous_);
      ++committing_;
    }
    ~Deferred() {
      --committing_;
      ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
    }
    Deferred(const Deferred&) = delete;
    Deferred& operator=(const Deferred&) = delete;

   private:
    sigset_t previous_{};
  };

 private:
  static void handle(int signal) {
    // A commit in another thread (this one blocks these signals while it commits) finishes first:
    // the set is then whole, and its temporaries are already gone.
    while (committing_.load() != 0) {
    }
    for (auto& slot : slots_) {
      if (const char* name = slot.load()) ::unlink(name);
    }
    for (auto slot = directory_slots_.rbegin(); slot != directory_slots_.rend(); ++slot) {
      if (const char* name = slot->load()) ::rmdir(name);  // deepest first; only while empty
    }
    for (std::size_t index = 0; index < std::size(signals); ++index) {
      if (signals[index] == signal) ::sigaction(signal, &previous_[index], nullptr);
    }
    ::raise(signal);  // the previous (default) action: the process ends as it would have
  }

  static inline std::mutex mutex_;
  static inline int holders_ = 0;
  static inline struct sigaction previous_[std::size(signals)] = {};
  static inline bool installed_[std::size(signals)] = {};
  static inline std::array<std::atomic<const char*>, 4096> slots_ = {};
  static inline std::array<std::atomic<const char*>, 256> directory_slots_ = {};
  static inline std::atomic<int> committing_ = 0;
};

// A new file `.NAME.saagen-XXXXXX` beside `path`, created exclusively (never through a link),
// holding `content`. The caller removes it on failure; so does a signal that ends the process.
class Temporaries {
 public:
  Temporaries() = default;
  Temporaries(const Temporaries&) = delete;
  Temporaries& operator=(const Temporaries&) = delete;
  ~Temporaries() {
    for (const auto& name : names_) {
      ::unlink(name->c_str());
      SignalCleanup::remove(name->c_str());
    }
  }

  const fs::path& create(const fs::path& path, std::string_view content) {
    // append() rather than operator+: GCC 12 reports a spurious -Wrestrict on the latter.
    std::string leaf = ".";
    leaf.append(path.filename().string()).append(".saagen-XXXXXX");
    auto owned = std::make_unique<std::string>((directory_of(path) / leaf).string());
    std::string& name = *owned;
    names_.push_back(std::move(owned));  // before mkostemp fills in the name: a signal in between finds it
    SignalCleanup::add(name.c_str());
    const int fd = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd < 0) {
      const int error = errno;
      SignalCleanup::remove(name.c_str());
      names_.pop_back();
      throw Error(fmt::format("{}: cannot write in this directory ({}); choose a writable output path", directory_of(path).string(),
                              error_text(error)));
    }
    paths_.emplace_back(name);
    try {
      if (::fchmod(fd, mode_) != 0) throw Error(fmt::format("{}: cannot set its permissions ({})", name, error_text(errno)));
      write_all(fd, content, path);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) {
      throw Error(fmt::format("{}: write failed ({}); free some space or choose another output path", path.string(), error_text(errno)));
    }
    return paths_.back();
  }

  // The temporaries have been renamed: nothing left to remove.
  void release() {
    for (const auto& name : names_) SignalCleanup::remove(name->c_str());
    names_.clear();
    paths_.clear();
  }

 private:
  SignalCleanup cleanup_;
  std::vector<std::unique_ptr<std::string>> names_;  // stable storage for the signal handler's slots
  std::vector<fs::path> paths_;
  mode_t mode_ = creation_mode();
};

// The directories a run creates for its outputs (missing ancestors included), removed again,
// deepest first and only while empty, unless the run succeeds; a signal removes them too.
class CreatedDirectories {
 public:
  CreatedDirectories() = default;
  CreatedDirectories(const CreatedDirectories&) = delete;
  CreatedDirectories& operator=(const CreatedDirectories&) = delete;
  ~CreatedDirectories() {
    for (auto name = created_.rbegin(); name != created_.rend(); ++name) {
      ::rmdir((*name)->c_str());
      SignalCleanup::remove_directory((*name)->c_str());
    }
  }

  void ensure(const fs::path& directory) {
    std::vector<fs::path> missing;
    struct stat status {};
    for (fs::path existing = directory; !existing.empty() && ::stat(existing.c_str(), &status) != 0;) {
      if (errno != ENOENT) throw cannot_create(directory, error_text(errno));
      missing.push_back(existing);
      if (existing.parent_path() == existing) break;
      existing = existing.parent_path();
    }
    for (auto path = missing.rbegin(); path != missing.rend(); ++path) {
      auto owned = std::make_unique<std::string>(path->string());
      SignalCleanup::add_directory(owned->c_str());  // before mkdir: a signal in between finds it
      if (::mkdir(owned->c_str(), 0777) != 0) {
        const int error = errno;
        SignalCleanup::remove_directory(owned->c_str());
        std::error_code ignored;
        if (error == EEXIST && fs::is_directory(*path, ignored)) continue;  // a concurrent run made it
        throw cannot_create(directory, error_text(error));
      }
      created_.push_back(std::move(owned));
    }
    std::error_code ignored;
    if (!fs::is_directory(directory, ignored)) throw cannot_create(directory, "not a directory");
  }

  // The run succeeded: the directories stay.
  void release() {
    for (const auto& name : created_) SignalCleanup::remove_directory(name->c_str());
    created_.clear();
  }

 private:
  static Error cannot_create(const fs::path& directory, const std::string& reason) {
    return Error(fmt::format("{}: cannot create the output directory ({}); choose a writable path", directory.string(), reason));
  }
  std::vector<std::unique_ptr<std::string>> created_;
};

void (*commit_hook)(CommitStep, std::size_t) = nullptr;

void run_commit_hook(CommitStep step, std::size_t index) {
  if (commit_hook) commit_hook(step, index);
}

// One file of a commit: its staged temporary, and where its previous bytes wait (a second hard
// link, or the file itself moved aside) until every file of the set is in place.
struct Replacement {
  std::string target;
  std::string staged;
  std::string backup;  // empty: there was no file at the target
  bool moved_aside = false;
  bool renamed = false;
};

// A fresh name `.NAME.saagen-XXXXXX` beside `path` that nothing holds (the placeholder mkstemp
// reserves is removed again: link() and rename() then take the name).
std::optional<std::string> free_name_beside(const std::string& path) {
  const fs::path target(path);
  std::string leaf = ".";
  leaf.append(target.filename().string()).append(".saagen-XXXXXX");
  std::string name = (directory_of(target) / leaf).string();
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  ::close(fd);
  ::unlink(name.c_str());
  return name;
}

// Why a file cannot be replaced, as the user can act on it.
std::string replace_failure(const std::string& target, int error) {
  if (error != EPERM && error != EACCES) return error_text(error);
  const int fd = ::open(target.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
  int flags = 0;
  const bool flagged = fd >= 0 && ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0 && (flags & (FS_IMMUTABLE_FL | FS_APPEND_FL)) != 0;
  if (fd >= 0) ::close(fd);
  if (flagged) return fmt::format("{}: the file is immutable or append-only (chattr -i/-a)", error_text(error));
  struct stat file {
  }, directory{};
  if (::lstat(target.c_str(), &file) == 0 && ::stat(directory_of(target).c_str(), &directory) == 0 && (directory.st_mode & S_ISVTX) &&
      file.st_uid != ::geteuid()) {
    return fmt::format("{}: another user's file in a sticky directory", error_text(error));
  }
  return error_text(error);
}

// Keeps the file at the target (if any) under a backup name, checking that it can be replaced:
// a second hard link keeps it in place; another user's file in a sticky directory, or one that
// cannot be linked (immutable, append-only, protected hard links), is moved aside instead, which
// the kernel refuses exactly when a rename over it would be refused. Returns 0 or an errno.
int keep_previous(Replacement& file) {
  struct stat target {
  }, directory{};
  if (::lstat(file.target.c_str(), &target) != 0) return errno == ENOENT ? 0 : errno;
  if (::stat(directory_of(file.target).c_str(), &directory) != 0) return errno;
  const bool foreign_in_sticky = (directory.st_mode & S_ISVTX) && target.st_uid != ::geteuid() && directory.st_uid != ::geteuid();
  for (int attempt = 0; attempt < 100; ++attempt) {
    const auto backup = free_name_beside(file.target);
    if (!backup) return errno;
    if (!foreign_in_sticky && ::link(file.target.c_str(), backup->c_str()) == 0) {
      file.backup = *backup;
      return 0;
    }
    if (!foreign_in_sticky && errno == EEXIST) continue;
    if (!foreign_in_sticky && errno == ENOENT) return 0;  // removed meanwhile
    if (::rename(file.target.c_str(), backup->c_str()) == 0) {
      file.backup = *backup;
      file.moved_aside = true;
      return 0;
    }
    return errno == ENOENT ? 0 : errno;
  }
  return EEXIST;
}

// Puts every file back as it was before the commit (renamed ones from their backups, new ones
// removed); returns the first file that could not be put back, with its errno.
std::optional<std::pair<std::size_t, int>> roll_back(std::vector<Replacement>& files) {
  std::optional<std::pair<std::size_t, int>> failure;
  for (std::size_t index = files.size(); index-- > 0;) {
    Replacement& file = files[index];
    int result = 0;
    if ((file.renamed || file.moved_aside) && !file.backup.empty())
      result = ::rename(file.backup.c_str(), file.target.c_str());
    else if (file.renamed)
      result = ::unlink(file.target.c_str());
    else if (!file.backup.empty())
      result = ::unlink(file.backup.c_str());
    if (result != 0 && !failure) failure = std::make_pair(index, errno);
  }
  return failure;
}

// Renames every staged file over its target, all or nothing: every previous file is kept first
// (which proves it replaceable), and a failure puts back the files already replaced. Signals
// that would end the process are deferred until the set is whole or restored.
void commit(std::vector<Replacement>& files) {
  std::optional<std::pair<std::size_t, int>> failure, restore_failure;
  {
    const SignalCleanup::Deferred deferred;
    for (std::size_t index = 0; index < files.size() && !failure; ++index) {
      if (const int error = keep_previous(files[index])) failure = std::make_pair(index, error);
    }
    for (std::size_t index = 0; index < files.size() && !failure; ++index) {
      if (::rename(files[index].staged.c_str(), files[index].target.c_str()) != 0) {
        failure = std::make_pair(index, errno);
        break;
      }
      files[index].renamed = true;
      run_commit_hook(CommitStep::renamed, index);
    }
    if (failure) {
      restore_failure = roll_back(files);
    } else {
      for (const Replacement& file : files) {
        if (!file.backup.empty()) ::unlink(file.backup.c_str());
      }
    }
  }
  if (!failure) return;
  const Replacement& failed = files[failure->first];
  const std::string reason = replace_failure(failed.target, failure->second);
  if (restore_failure) {
    const Replacement& lost = files[restore_failure->first];
    throw Error(fmt::format("{}: cannot be replaced ({}); {} could not be put back ({}), its previous bytes are in {}", failed.target,
                            reason, lost.target, error_text(restore_failure->second), lost.backup));
  }
  throw Error(fmt::format("{}: cannot be replaced ({}); nothing was changed", failed.target, reason));
}

}  // namespace

bool written_by_saagen(const fs::path& path, std::string_view bytes) {
  // The format decides where the tag must be; a tag anywhere else (a README quoting it) is not.
  if (bytes.substr(0, 12) == ktx2_identifier()) return ktx2_written_by_saagen(bytes) || sidecar_vouches_for(path, bytes);
  if (bytes.substr(0, 8) == png_signature()) return png_written_by_saagen(bytes) || sidecar_vouches_for(path, bytes);
  if (is_spirv(bytes)) return spirv_written_by_saagen(bytes) || sidecar_vouches_for(path, bytes);
  if (is_json_object(bytes)) return json_written_by_saagen(bytes) || sidecar_vouches_for(path, bytes);
  return text_written_by_saagen(bytes) || sidecar_vouches_for(path, bytes);
}

OutputFile ownership_sidecar(const fs::path& path, std::string_view bytes, std::string_view description) {
  return {sidecar_path(path),
          fmt::format("{} sidecar of {}\n{}\n{}\n", output_tag, path.filename().string(), sidecar_fingerprint(bytes), description)};
}

void check_output_paths(const std::vector<fs::path>& paths, bool force, const std::vector<fs::path>& inputs) {
  check_named_once(paths);
  check_not_inputs(paths, inputs);
  for (const fs::path& path : paths) needs_writing(path, std::nullopt, force);
}

WriteReport write_outputs(const std::vector<OutputFile>& files, bool force, const std::vector<fs::path>& inputs) {
  std::vector<fs::path> paths;
  for (const OutputFile& file : files) paths.push_back(file.path);
  check_named_once(paths);
  check_not_inputs(paths, inputs);

  WriteReport report;
  std::vector<const OutputFile*> to_write;
  for (const OutputFile& file : files) {
    if (needs_writing(file.path, std::string_view(file.content), force))
      to_write.push_back(&file);
    else
      report.unchanged.push_back(file.path);
  }

  CreatedDirectories directories;
  Temporaries temporaries;
  std::vector<Replacement> replacements;
  try {
    for (const OutputFile* file : to_write) {
      directories.ensure(directory_of(file->path));
      Replacement replacement;
      replacement.target = file->path.string();
      replacement.staged = temporaries.create(file->path, file->content).string();
      replacements.push_back(std::move(replacement));
      run_commit_hook(CommitStep::staged, replacements.size() - 1);
    }
  } catch (const Error& error) {
    // The temporaries and the new directories go as this unwinds.
    throw Error(fmt::format("{}; nothing was changed", error.what()));
  }
  commit(replacements);
  temporaries.release();
  directories.release();
  for (const OutputFile* file : to_write) report.written.push_back(file->path);
  return report;
}

void set_commit_hook(void (*hook)(CommitStep step, std::size_t index)) { commit_hook = hook; }

}  // namespace saagen
