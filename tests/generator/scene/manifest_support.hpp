// The helpers of test_manifest's sources (test_manifest_*.cpp, one executable): the example
// manifest, a manifest parsed from text, the one-line error it gives, and what a bundle defines.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace saagen::test::manifest {

inline const std::filesystem::path example_manifest = std::filesystem::path(SAAGEN_SOURCE_DIR) / "examples" / "scene.saagen.toml";

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

inline saagen::Manifest parse(const std::string& text) { return saagen::parse_manifest(text, "scene.toml", Catalogue::builtin()); }

// The message parse (and plan) throws for `text`, or "" when it is accepted.
inline std::string error_of(const std::string& text) {
  try {
    const saagen::Manifest manifest = parse(text);
    (void)saagen::plan_scene(Catalogue::builtin(), manifest);
  } catch (const saagen::Error& error) {
    return error.what();
  }
  return "";
}

inline const std::string header = "targets = [\"glsl\"]\n";
inline const std::string forward_material = "[[material]]\nname = \"m\"\npath = \"forward\"\n";

// Names of the functions defined (not merely declared in a comment) in an emitted file.
inline std::set<std::string> defined_functions(const std::string& content, const std::string& prefix) {
  std::set<std::string> names;
  const std::regex definition("^[A-Za-z0-9_]+ " + prefix + "([A-Za-z0-9_]+)\\(");
  std::istringstream lines(content);
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (std::regex_search(line, match, definition)) names.insert(match[1]);
  }
  return names;
}

inline std::set<std::string> closure_names(const std::vector<std::string>& roots) {
  std::set<std::string> names;
  for (const saagen::Function* function : Catalogue::builtin().closure(roots)) names.insert(function->name);
  return names;
}

inline std::vector<saagen::EmittedFile> emit_text(const std::string& text) {
  const saagen::Manifest manifest = parse(text);
  return saagen::emit_scene(Catalogue::builtin(), manifest, saagen::plan_scene(Catalogue::builtin(), manifest));
}

}  // namespace saagen::test::manifest
