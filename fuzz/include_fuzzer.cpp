// libFuzzer target: #include expansion with its preprocessor logic (expand_includes: comments,
// #if/#ifdef/#ifndef/#elif/#else/#endif over #define/#undef, guards, #pragma once, the depth and
// total budgets). The input is up to 8 files separated by NUL bytes, named 0.glsl, 1.glsl, ...;
// 0.glsl is the root; <saagen/x> is the one generated name that exists. Rejected input must fail
// with one line starting with a file's name and line; an accepted expansion stays in its budget
// and every deferred error maps back from its #error token.
#include "fuzz_support.hpp"

#include "saagen/error.hpp"
#include "saagen/io/include_expansion.hpp"

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using saagen::fuzz::finding;
  constexpr const char* target = "include_fuzzer";
  std::map<std::string, std::string> files;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  for (std::size_t at = 0, index = 0; index < 8; ++index) {
    const auto end = std::min(input.find('\0', at), input.size());
    files[std::to_string(index) + ".glsl"] = std::string(input.substr(at, end - at));
    if (end == input.size()) break;
    at = end + 1;
  }
  const saagen::IncludeSources sources{
      [&](const std::string& name, const saagen::IncludeFile&) -> std::shared_ptr<const saagen::IncludeFile> {
        const auto found = files.find(name);
        if (found == files.end()) return nullptr;
        return std::make_shared<const saagen::IncludeFile>(saagen::IncludeFile{name, name, found->second});
      },
      [](const std::string& name) -> std::string {
        if (name != "saagen/x") throw saagen::Error("unknown saagen include '" + name + "'");
        return "float generated;\n";
      }};
  saagen::IncludeLimits limits;
  limits.total_bytes = std::size_t{1} << 20;
  limits.includes = 4096;
  saagen::IncludeExpansion expansion;
  try {
    expansion = saagen::expand_includes({"0.glsl", "0.glsl", files["0.glsl"]}, sources, limits);
  } catch (const saagen::Error& error) {
    const std::string_view message = error.what();
    // FILE:LINE: with FILE one of the inputs.
    const auto dot = message.find(".glsl:");
    const bool located = dot != std::string_view::npos && dot > 0 && files.count(std::string(message.substr(0, dot + 5))) &&
                         dot + 6 < message.size() && std::isdigit(static_cast<unsigned char>(message[dot + 6]));
    if (!located) finding(target, "error without FILE:LINE:", message);
    saagen::fuzz::check_message(target, message, message.substr(0, dot + 6));
    return 0;
  }
  std::size_t total = 0;
  for (const auto& piece : expansion.pieces) total += piece.text.size();
  if (total > limits.total_bytes) finding(target, "expansion beyond its budget", std::to_string(total));
  for (std::size_t index = 0; index < expansion.deferred_errors.size(); ++index) {
    const std::string& error = expansion.deferred_errors[index];
    if (error.find('\n') != std::string::npos) finding(target, "deferred error spans lines", error);
    const auto back = saagen::deferred_include_error(expansion, "0.glsl:1: '#error' : saagen_unresolved_include_" + std::to_string(index));
    if (back != error) finding(target, "a deferred error does not map back", error);
  }
  return 0;
}
