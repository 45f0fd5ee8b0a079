// Shared by the libFuzzer targets: a finding aborts with a one-line reason (libFuzzer keeps the
// input), and every saagen::Error a target accepts must be one line.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace saagen::fuzz {

[[noreturn]] inline void finding(const char* target, const char* what, std::string_view detail) {
  std::fprintf(stderr, "%s: %s: %.*s\n", target, what, static_cast<int>(detail.size()), detail.data());
  std::abort();
}

// saagen reports bad input in one line that starts with `prefix` (the file or the format).
// SAAGEN_FUZZ_VERBOSE=1 prints each rejection (to see what a corpus file exercises).
inline void check_message(const char* target, std::string_view message, std::string_view prefix) {
  if (std::getenv("SAAGEN_FUZZ_VERBOSE"))
    std::fprintf(stderr, "%s: rejected: %.*s\n", target, static_cast<int>(message.size()), message.data());
  if (message.rfind(prefix, 0) != 0) finding(target, "error without its prefix", message);
  if (message.find('\n') != std::string_view::npos) finding(target, "error message spans lines", message);
}

}  // namespace saagen::fuzz
