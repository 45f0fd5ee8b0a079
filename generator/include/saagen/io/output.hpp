// Writing generated files: one layer for every command that writes. All or nothing, atomically,
// only when the bytes change, never over a file saagen did not write (unless forced), and never
// through a symbolic link, so that a build system does not rebuild needlessly, never sees a
// half-written file, and a planted link cannot redirect a write outside the target.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

struct OutputFile {
  std::filesystem::path path;
  std::string content;
};

struct WriteReport {
  std::vector<std::filesystem::path> written;
  std::vector<std::filesystem::path> unchanged;
};

// The tag that marks outputs without an emission marker line as saagen's (report pages, plots
// and PNG text chunks, compiled SPIR-V, JSON tables, sidecars). Emitted shader files carry the
// marker line of emitter.hpp instead; KTX2 files a "saagen.*" key/value entry.
inline constexpr std::string_view output_tag = "saagen-output:";

// Whether bytes found at `path` were written by saagen: an emission marker line, the output tag,
// a KTX2 file with a "saagen.*" key, or a sidecar `<path>.saagen` vouching for these bytes.
bool written_by_saagen(const std::filesystem::path& path, std::string_view bytes);

// The sidecar that vouches for a raw output (no room for a tag in its format): an OutputFile
// named `<path>.saagen` holding the tag, a description and the bytes' size and hash.
OutputFile ownership_sidecar(const std::filesystem::path& path, std::string_view bytes, std::string_view description);

// Checks, before any long work, that every path could be written: not empty, named once (by
// file identity: two names of one file, through a linked directory or a hard link, are one), not
// one of the command's `inputs` (compared by device and inode, not by name; not even with
// `force`), not a directory, a symbolic link or a special file, saagen's own unless `force`, and
// inside a directory that exists and is writable or can be created. Throws saagen::Error (one line).
void check_output_paths(const std::vector<std::filesystem::path>& paths, bool force, const std::vector<std::filesystem::path>& inputs = {});

// Writes every file through a temporary created exclusively (mkstemp) in its own directory and a
// rename, after checking every path as check_output_paths does (`inputs` included). All or
// nothing: nothing is renamed until every temporary is complete; then every file about to be
// replaced is kept under a second name (which proves it replaceable: not immutable, not another
// user's in a sticky directory) before the first rename, and a failed rename puts back the files
// already replaced. On any failure (full disk included) every temporary and every directory the
// run created is removed and saagen::Error names the file and says nothing was changed.
// SIGINT, SIGTERM, SIGHUP and SIGXFSZ while staging remove the temporaries and new directories;
// during the renames they wait until the set is whole. A symbolic link at a path is refused;
// with `force` the link itself is replaced (what it points to is never written).
WriteReport write_outputs(const std::vector<OutputFile>& files, bool force, const std::vector<std::filesystem::path>& inputs = {});

// For tests: called after each file of write_outputs is staged and after each is renamed into
// place (index in the order of the files written), to interrupt or disturb a commit there.
enum class CommitStep { staged, renamed };
void set_commit_hook(void (*hook)(CommitStep step, std::size_t index));

}  // namespace saagen
