// Reading the keys of an embedded JSON table (a target's syntax table, a language's table) with
// one line that names the table when a key is missing or of the wrong type.
#pragma once

#include "saagen/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace saagen::table_keys {

// `kind` names the table in the message: "target", "language".
inline const nlohmann::json& require(const nlohmann::json& object, const char* key, std::string_view source, std::string_view kind) {
  if (!object.is_object() || !object.contains(key)) throw Error(fmt::format("{}: missing key '{}' in the {} table", source, key, kind));
  return object.at(key);
}

inline std::string require_string(const nlohmann::json& object, const char* key, std::string_view source, std::string_view kind) {
  const nlohmann::json& value = require(object, key, source, kind);
  if (!value.is_string()) throw Error(fmt::format("{}: key '{}' of the {} table must be a string", source, key, kind));
  return value.get<std::string>();
}

}  // namespace saagen::table_keys
