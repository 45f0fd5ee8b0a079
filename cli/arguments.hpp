// Checks of command-line arguments shared by the commands, done before anything is read or
// written: each problem is one saagen::Error line naming the option.
#pragma once

#include "saagen/error.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace saagen::cli {

// A repeatable option (e.g. --variant) must not name a value twice.
inline void check_named_once(std::string_view option, const std::vector<std::string>& values) {
  for (auto value = values.begin(); value != values.end(); ++value) {
    if (std::find(values.begin(), value, *value) != value) {
      throw Error(fmt::format("{} {}: named twice; name each value once", option, *value));
    }
  }
}

// A value must be given: CLI11 takes an empty one ("--scale ''") as the option's default.
inline CLI::Validator value_given() {
  return CLI::Validator([](std::string& text) { return text.empty() ? std::string("empty; pass a value") : std::string(); }, "", "given");
}

// An output directory or file must be named: an empty one would write into the current directory.
inline void check_output_named(std::string_view option, const std::string& path) {
  if (path.empty()) throw Error(fmt::format("{}: empty; pass the output path", option));
}

// A whole decimal number ("nan" and "inf" are read, and left to the range checks); an empty or
// partly numeric text is refused.
inline double parse_number(std::string_view option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || std::isspace(static_cast<unsigned char>(text.front()))) {
    throw Error(fmt::format("{} '{}': not a number; pass a decimal number", option, text));
  }
  return value;
}

// A whole decimal number in [0, 2^64 - 1], nothing else: no sign, no exponent, no fraction, no
// spaces, no wrap-around (-1) or saturation (2^64).
inline std::uint64_t parse_unsigned(std::string_view option, const std::string& text) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw Error(fmt::format("{} '{}': not a whole number in [0, 18446744073709551615]; pass a decimal number without sign or exponent",
                            option, text));
  }
  return value;
}

// The regular files in a directory, sorted; an unreadable directory is one line, not an exception
// from std::filesystem.
inline std::vector<std::filesystem::path> regular_files_in(const std::filesystem::path& directory) {
  std::error_code error;
  std::vector<std::filesystem::path> files;
  for (std::filesystem::directory_iterator entry(directory, error), end; !error && entry != end; entry.increment(error)) {
    std::error_code kind_error;
    if (entry->is_regular_file(kind_error)) files.push_back(entry->path());
  }
  if (error) throw Error(fmt::format("{}: cannot be listed ({}); check its permissions", directory.string(), error.message()));
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace saagen::cli
