// Reading untrusted input files (manifests, trade tables, shader sources, normal maps, KTX2):
// regular files only, read with a size limit, so that `/dev/zero`, a FIFO or a directory is
// refused at once with one line instead of hanging or exhausting memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace saagen {

// Size limits of the files saagen reads.
inline constexpr std::size_t manifest_size_limit = std::size_t{1} << 20;  // 1 MiB
inline constexpr std::size_t table_size_limit = std::size_t{64} << 20;    // trade and cost tables
inline constexpr std::size_t source_size_limit = std::size_t{16} << 20;   // shader sources
inline constexpr std::size_t image_size_limit = std::size_t{256} << 20;   // PPM, KTX2

// The bytes of a regular file of at most `limit` bytes. Throws saagen::Error naming the file:
// missing, a directory, not a regular file (device, FIFO, socket), unreadable, or too large.
// `what` completes "pass ..." in the messages (e.g. "a scene manifest").
std::string read_input_file(const std::filesystem::path& path, std::size_t limit, std::string_view what);

}  // namespace saagen
