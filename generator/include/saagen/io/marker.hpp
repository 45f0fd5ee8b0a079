// The marker line saagen writes into every snippet, library and pass ("// saagen-marker:
// target=... variants=... prefix=..."), and reads back to validate a file or recognise it as its
// own output.
#pragma once

#include "saagen/domain.hpp"
#include "saagen/precision.hpp"

#include <compare>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen {

// What a marker's `target=` names: a snippet of a target table (glsl, gles, hlsl, wgsl), a
// deferred pass's source written in a target table's language ("pass-" and the table's name:
// pass-glsl, pass-hlsl), or one of the binary products, whose pseudo-targets are spelled here
// and nowhere else.
enum class OutputKind { snippet, pass_source, spirv_library, pass_spirv };

// The prefix of a pass source's `target=`, before its table's name.
inline constexpr std::string_view kPassSourcePrefix = "pass-";

// The `target=` of a binary product's marker: "spirv" (library modules and their headers, and the
// `--target` that asks for them), "pass-spirv" (the deferred pass's SPIR-V); "" for the kinds
// that name a table.
constexpr std::string_view marker_target(OutputKind kind) {
  switch (kind) {
    case OutputKind::spirv_library:
      return "spirv";
    case OutputKind::pass_spirv:
      return "pass-spirv";
    case OutputKind::snippet:
    case OutputKind::pass_source:
      break;
  }
  return "";
}

// The kind a marker target names: a binary product's pseudo-target, a pass source ("pass-" and a
// table's name), else a snippet.
constexpr OutputKind output_kind(std::string_view target) {
  for (OutputKind kind : {OutputKind::spirv_library, OutputKind::pass_spirv}) {
    if (target == marker_target(kind)) return kind;
  }
  if (target.size() > kPassSourcePrefix.size() && target.substr(0, kPassSourcePrefix.size()) == kPassSourcePrefix)
    return OutputKind::pass_source;
  return OutputKind::snippet;
}

// What an emission is for, as a typed value: a snippet of the target table `table`, or a product
// (its pseudo-target, `table` empty). A marker's `target=` and an emission's `--target` (and
// EmitOptions::target) are read into one once, where the text enters: from text it converts
// through named().
struct OutputTarget {
  OutputKind kind = OutputKind::snippet;
  std::string table;

  OutputTarget() = default;
  OutputTarget(OutputKind kind, std::string table) : kind(kind), table(std::move(table)) {}
  OutputTarget(const char* text) : OutputTarget(named(text)) {}
  OutputTarget(const std::string& text) : OutputTarget(named(text)) {}

  static OutputTarget snippet(std::string table) { return {OutputKind::snippet, std::move(table)}; }
  // The source of a deferred pass written in table `table`'s language.
  static OutputTarget pass_source(std::string table) { return {OutputKind::pass_source, std::move(table)}; }
  static OutputTarget product(OutputKind kind) { return {kind, {}}; }
  // The `target=` text a marker names: a product's pseudo-target, a pass source, else a table's name.
  static OutputTarget named(std::string_view text) {
    switch (output_kind(text)) {
      case OutputKind::snippet:
        return snippet(std::string(text));
      case OutputKind::pass_source:
        return pass_source(std::string(text.substr(kPassSourcePrefix.size())));
      default:
        return product(output_kind(text));
    }
  }
  bool is_snippet() const { return kind == OutputKind::snippet; }
  // The text form: the table's name of a snippet, "pass-" and it of a pass source, the
  // pseudo-target of a product.
  std::string name() const {
    if (is_snippet()) return table;
    if (kind == OutputKind::pass_source) return std::string(kPassSourcePrefix) + table;
    return std::string(marker_target(kind));
  }
  bool operator==(const OutputTarget&) const = default;
  auto operator<=>(const OutputTarget&) const = default;  // an order for maps keyed by target
};

// What one emitted file holds, as written in its marker line, so that a file on disk can be
// validated (and recognised as saagen's) without the options that produced it.
struct EmissionMarker {
  OutputTarget target;
  std::vector<std::string> variants;
  std::string prefix;
  std::map<std::string, double> option_values;
  Precision precision = Precision::fp32;
  bool guards = true;
  // A bundle's public functions (`functions=` in the marker); empty: every public function of
  // `variants` (a per-variant file).
  std::vector<std::string> functions;
  Domain domain = Domain::alpha2;  // `domain=` in the marker, written when not alpha2
  std::string import_path{};       // `import_path=` in the marker, written when set
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
