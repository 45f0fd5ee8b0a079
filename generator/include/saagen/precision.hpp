// The floating-point precision of an emission as a typed value: what `--precision`, manifests,
// include queries, markers, the templates' `precisions:` lists and the target tables give as text
// is converted once, where it is read (parse_precision, precision_named), and the library
// compares these values, never text.
#pragma once

#include "saagen/error.hpp"

#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// fp32 (every target's default), fp16 (GLSL float16_t, GLSL ES mediump, WGSL f16) and min16
// (HLSL min16float): the forms the target tables' "precisions" may define.
enum class Precision { fp32, fp16, min16 };

inline constexpr Precision every_precision_kind[] = {Precision::fp32, Precision::fp16, Precision::min16};
// The ids the text forms use, in the enum's order: the one table of the names.
inline constexpr std::string_view precision_ids[] = {"fp32", "fp16", "min16"};
static_assert(std::size(precision_ids) == std::size(every_precision_kind));

constexpr std::string_view to_string(Precision precision) { return precision_ids[static_cast<std::size_t>(precision)]; }

// The precision an id names, or nothing.
constexpr std::optional<Precision> precision_named(std::string_view id) {
  for (const Precision precision : every_precision_kind) {
    if (to_string(precision) == id) return precision;
  }
  return std::nullopt;
}

// "fp32, fp16, min16": what a message offers.
inline std::string precision_id_list() {
  std::string list;
  for (const std::string_view id : precision_ids) list += (list.empty() ? "" : ", ") + std::string(id);
  return list;
}

// The ids of `precisions`, in their order (messages and listings).
inline std::vector<std::string> precision_names(const std::vector<Precision>& precisions) {
  std::vector<std::string> names;
  for (const Precision precision : precisions) names.emplace_back(to_string(precision));
  return names;
}

// Narrower than fp32: literals and constants take their half-precision forms.
constexpr bool is_half(Precision precision) { return precision != Precision::fp32; }

// The precision `text` names; throws saagen::Error "<option> <text>: ..." naming the ids otherwise.
inline Precision parse_precision(std::string_view text, std::string_view option = "--precision") {
  if (const auto precision = precision_named(text)) return *precision;
  throw Error(std::string(option) + " " + std::string(text) + ": unknown precision; use one of " + precision_id_list());
}

}  // namespace saagen
