// Writing generated files: all or nothing, atomically, and only when the bytes change, so that
// a build system does not rebuild needlessly and never sees a half-written file.
#pragma once

#include <filesystem>
#include <string>
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

// Writes every file through a temporary in the same directory and a rename. Before writing
// anything it checks that each existing target either was written by saagen (holds the marker
// line) or `force` is set, and that the directories can be created and written; on any problem
// it throws saagen::Error and leaves the output directory as it was.
WriteReport write_outputs(const std::vector<OutputFile>& files, bool force);

}  // namespace saagen
