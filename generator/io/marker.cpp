#include "saagen/io/marker.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <sstream>

namespace saagen {
namespace {

constexpr std::string_view marker_tag = "// saagen-marker:";

}  // namespace

std::string decimal_literal(double value) {
  if (value == 0.0) value = 0.0;  // -0.0 (kappa = -0.0) is written 0.0
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

std::optional<double> parse_double(std::string_view text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string marker_line(const EmissionMarker& marker) {
  std::string line =
      fmt::format("{} target={} variants={} prefix={}", marker_tag, marker.target.name(), fmt::join(marker.variants, ","), marker.prefix);
  for (const auto& [option, value] : marker.option_values) line += fmt::format(" {}={}", option, decimal_literal(value));
  if (marker.precision != Precision::fp32) line += fmt::format(" precision={}", to_string(marker.precision));
  if (!marker.guards) line += " guards=off";
  if (!marker.functions.empty()) line += fmt::format(" functions={}", fmt::join(marker.functions, ","));
  if (marker.domain != Domain::alpha2) line += fmt::format(" domain={}", to_string(marker.domain));
  if (!marker.import_path.empty()) line += " import_path=" + marker.import_path;
  return line;
}

std::optional<EmissionMarker> find_marker(std::string_view content) {
  const auto start = content.find(marker_tag);
  if (start == std::string_view::npos) return std::nullopt;
  auto end = content.find('\n', start);
  if (end == std::string_view::npos) end = content.size();
  std::istringstream fields{std::string(content.substr(start + marker_tag.size(), end - start - marker_tag.size()))};
  EmissionMarker marker;
  for (std::string field; fields >> field;) {
    const auto equals = field.find('=');
    if (equals == std::string::npos) return std::nullopt;
    const std::string key = field.substr(0, equals);
    const std::string value = field.substr(equals + 1);
    if (key == "target")
      marker.target = OutputTarget::named(value);
    else if (key == "prefix")
      marker.prefix = value;
    else if (key == "precision") {
      const auto precision = precision_named(value);
      if (!precision) return std::nullopt;
      marker.precision = *precision;
    } else if (key == "guards")
      marker.guards = value != "off";
    else if (key == "domain") {
      const auto domain = domain_named(value);
      if (!domain) return std::nullopt;
      marker.domain = *domain;
    } else if (key == "import_path")
      marker.import_path = value;
    else if (key == "functions") {
      std::istringstream names(value);
      for (std::string name; std::getline(names, name, ',');) marker.functions.push_back(name);
    } else if (key == "variants") {
      std::istringstream ids(value);
      for (std::string id; std::getline(ids, id, ',');) marker.variants.push_back(id);
    } else if (const auto number = parse_double(value))
      marker.option_values[key] = *number;
    else
      return std::nullopt;
  }
  if (marker.target.name().empty() || marker.prefix.empty() || marker.variants.empty()) return std::nullopt;
  return marker;
}

}  // namespace saagen
