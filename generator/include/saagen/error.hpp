// saagen reports every user-facing problem as one line: where, what, and what to do.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace saagen {

// The longest message printed; a longer one (a huge path or argument quoted in it) keeps its
// beginning and its end (where it says what to do) around a note of how much was left out.
inline constexpr std::size_t max_message_bytes = 1024;

// A message as one printable line: control characters escaped (\n, \r, \t, \xHH), so that text
// quoted from the command line or a file can neither break the line nor drive the terminal, and
// at most max_message_bytes long.
inline std::string one_line(std::string_view message) {
  std::string line;
  line.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n')
      line += "\\n";
    else if (c == '\r')
      line += "\\r";
    else if (c == '\t')
      line += "\\t";
    else if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      line += escaped;
    } else
      line += c;
  }
  if (line.size() <= max_message_bytes) return line;
  constexpr std::size_t keep = (max_message_bytes - 64) / 2;
  const std::size_t left_out = line.size() - 2 * keep;
  return line.substr(0, keep) + " [... " + std::to_string(left_out) + " bytes left out ...] " + line.substr(line.size() - keep);
}

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(one_line(message)) {}
  explicit Error(const char* message) : Error(std::string(message)) {}
};

}  // namespace saagen
