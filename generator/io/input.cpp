#include "saagen/io/input.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace saagen {
namespace {

std::string size_text(std::size_t bytes) {
  return bytes >= (std::size_t{1} << 20) ? fmt::format("{} MiB", bytes >> 20) : fmt::format("{} KiB", bytes >> 10);
}

// Opens without blocking (a FIFO would wait for a writer) and checks the kind and size.
int open_regular(const std::filesystem::path& path, std::size_t limit, std::string_view what) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT) throw Error(fmt::format("{}: cannot be read (no such file); pass {}", path.string(), what));
    throw Error(fmt::format("{}: cannot be read ({}); check its permissions", path.string(), std::generic_category().message(error)));
  }
  struct stat status {};
  std::string problem;
  if (::fstat(fd, &status) != 0)
    problem = "cannot be inspected";
  else if (S_ISDIR(status.st_mode))
    problem = "is a directory";
  else if (!S_ISREG(status.st_mode))
    problem = "is not a regular file (a device, FIFO or socket)";
  else if (static_cast<std::size_t>(status.st_size) > limit)
    problem = fmt::format("is larger than {}", size_text(limit));
  if (!problem.empty()) {
    ::close(fd);
    throw Error(fmt::format("{}: {}; pass {}", path.string(), problem, what));
  }
  return fd;
}

}  // namespace

std::string read_input_file(const std::filesystem::path& path, std::size_t limit, std::string_view what) {
  const int fd = open_regular(path, limit, what);
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t count = ::read(fd, buffer, sizeof buffer);
    if (count < 0 && errno == EINTR) continue;
    if (count < 0) {
      const int error = errno;
      ::close(fd);
      throw Error(fmt::format("{}: cannot be read ({}); check its permissions", path.string(), std::generic_category().message(error)));
    }
    if (count == 0) break;
    bytes.append(buffer, static_cast<std::size_t>(count));
    if (bytes.size() > limit) {  // the file grew after fstat
      ::close(fd);
      throw Error(fmt::format("{}: is larger than {}; pass {}", path.string(), size_text(limit), what));
    }
  }
  ::close(fd);
  return bytes;
}

}  // namespace saagen
