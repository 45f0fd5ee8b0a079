#include "saagen/output.hpp"

#include "saagen/emitter.hpp"
#include "saagen/error.hpp"

#include <fmt/format.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>
#include <unistd.h>

namespace saagen {
namespace {

namespace fs = std::filesystem;

std::optional<std::string> read_existing(const fs::path& path) {
  std::error_code error;
  if (!fs::exists(path, error)) return std::nullopt;
  if (!fs::is_regular_file(path, error)) {
    throw Error(fmt::format("{}: exists and is not a regular file; remove it or choose another output directory", path.string()));
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw Error(fmt::format("{}: cannot be read; check its permissions", path.string()));
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

void ensure_directory(const fs::path& directory) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error || !fs::is_directory(directory)) {
    throw Error(fmt::format("{}: cannot create the output directory ({}); choose a writable path", directory.string(),
                            error ? error.message() : "not a directory"));
  }
}

fs::path temporary_path_for(const fs::path& path) {
  return path.parent_path() / fmt::format(".{}.saagen-tmp-{}", path.filename().string(), ::getpid());
}

void write_temporary(const fs::path& temporary, const std::string& content) {
  std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
  if (!stream) throw Error(fmt::format("{}: cannot write in this directory; choose a writable output path", temporary.parent_path().string()));
  stream.write(content.data(), static_cast<std::streamsize>(content.size()));
  stream.flush();
  if (!stream) throw Error(fmt::format("{}: write failed (disk full?)", temporary.string()));
}

}  // namespace

WriteReport write_outputs(const std::vector<OutputFile>& files, bool force) {
  WriteReport report;
  std::vector<const OutputFile*> to_write;
  for (const OutputFile& file : files) {
    const auto existing = read_existing(file.path);
    if (existing && *existing == file.content) {
      report.unchanged.push_back(file.path);
      continue;
    }
    if (existing && !force && !find_marker(*existing)) {
      throw Error(fmt::format("{}: exists and was not written by saagen; refusing to overwrite it (use --force)", file.path.string()));
    }
    to_write.push_back(&file);
  }

  std::vector<fs::path> temporaries;
  const auto remove_temporaries = [&temporaries] {
    for (const fs::path& temporary : temporaries) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
    }
  };
  try {
    for (const OutputFile* file : to_write) {
      ensure_directory(file->path.has_parent_path() ? file->path.parent_path() : fs::path("."));
      temporaries.push_back(temporary_path_for(file->path));
      write_temporary(temporaries.back(), file->content);
    }
    for (std::size_t index = 0; index < to_write.size(); ++index) {
      std::error_code error;
      fs::rename(temporaries[index], to_write[index]->path, error);
      if (error) throw Error(fmt::format("{}: cannot replace the file ({})", to_write[index]->path.string(), error.message()));
      report.written.push_back(to_write[index]->path);
    }
  } catch (...) {
    remove_temporaries();
    throw;
  }
  return report;
}

}  // namespace saagen
