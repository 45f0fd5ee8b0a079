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

// What a marker's `target=` names: a snippet of a target table (glsl, gles, hlsl, wgsl), or one of
// the binary products, whose pseudo-targets are spelled here and nowhere else.
enum class OutputKind { snippet, spirv_library, pass_glsl, pass_hlsl, pass_spirv };

// The `target=` of a product's marker: "spirv" (library modules and their headers, and the
// `--target` that asks for them), "pass-glsl", "pass-hlsl", "pass-spirv" (the deferred pass files).
constexpr std::string_view marker_target(OutputKind kind) {
  switch (kind) {
    case OutputKind::spirv_library:
      return "spirv";
    case OutputKind::pass_glsl:
      return "pass-glsl";
    case OutputKind::pass_hlsl:
      return "pass-hlsl";
    case OutputKind::pass_spirv:
      return "pass-spirv";
    case OutputKind::snippet:
      break;
  }
  return "";
}

// The kind a marker target names: a product's pseudo-target, else a snippet.
constexpr OutputKind output_kind(std::string_view target) {
  for (OutputKind kind : {OutputKind::spirv_library, OutputKind::pass_glsl, OutputKind::pass_hlsl, OutputKind::pass_spirv}) {
    if (target == marker_target(kind)) return kind;
  }
  return OutputKind::snippet;
}

// A deferred pass source's kind is named after the target table it is written in: "pass-glsl" is
// the pass of the target glsl. The target a pass-source kind names ("" for another kind), and the
// kind of a target's pass source (snippet when none is spelled for it).
constexpr std::string_view pass_source_target(OutputKind kind) {
  constexpr std::string_view pass = "pass-";
  if (kind != OutputKind::pass_glsl && kind != OutputKind::pass_hlsl) return "";
  return marker_target(kind).substr(pass.size());
}
constexpr OutputKind pass_source_kind(std::string_view target) {
  for (OutputKind kind : {OutputKind::pass_glsl, OutputKind::pass_hlsl}) {
    if (pass_source_target(kind) == target) return kind;
  }
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
  static OutputTarget product(OutputKind kind) { return {kind, {}}; }
  // The `target=` text a marker names: a product's pseudo-target, else a table's name.
  static OutputTarget named(std::string_view text) {
    const OutputKind kind = output_kind(text);
    return kind == OutputKind::snippet ? snippet(std::string(text)) : product(kind);
  }
  bool is_snippet() const { return kind == OutputKind::snippet; }
  // The text form: the pseudo-target of a product, the table's name of a snippet.
  std::string name() const { return is_snippet() ? table : std::string(marker_target(kind)); }
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
