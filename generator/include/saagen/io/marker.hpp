// The marker line saagen writes into every snippet, library and pass ("// saagen-marker:
// target=... variants=... prefix=..."), and reads back to validate a file or recognise it as its
// own output.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// What one emitted file holds, as written in its marker line, so that a file on disk can be
// validated (and recognised as saagen's) without the options that produced it.
struct EmissionMarker {
  std::string target;
  std::vector<std::string> variants;
  std::string prefix;
  std::map<std::string, double> option_values;
  std::string precision = "fp32";
  bool guards = true;
  // A bundle's public functions (`functions=` in the marker); empty: every public function of
  // `variants` (a per-variant file).
  std::vector<std::string> functions;
  std::string domain = "alpha2";  // `domain=` in the marker, written when not alpha2
  std::string import_path{};      // `import_path=` in the marker, written when set
};

// The marker line written into every emitted file, and its parser (nullopt when the text holds
// no marker: the file was not written by saagen).
std::string marker_line(const EmissionMarker& marker);
std::optional<EmissionMarker> find_marker(std::string_view content);

// Shortest text that reads back as the same double and is a floating-point literal in GLSL,
// HLSL and WGSL (it always has a '.' or an exponent): the marker's numbers and the emitted
// constants.
std::string decimal_literal(double value);

// The whole of `text` as a double, or nothing.
std::optional<double> parse_double(std::string_view text);

}  // namespace saagen
