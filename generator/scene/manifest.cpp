#include "saagen/scene/manifest.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/scene/cost_tables.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/validation.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

// toml++ is used header-only and privately: nothing of it appears in saagen's headers, so the
// installed library adds no dependency for engines.
#define TOML_HEADER_ONLY 1
#define TOML_EXCEPTIONS 1
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

namespace saagen {
namespace {

constexpr const char* kSourceRule = "a string: where the scene or material comes from (informational)";

// `lights`, scene-wide and per material.
std::string lights_rule(std::string_view default_text) {
  return fmt::format(
      "an integer from 1 to {}: the lights that shade a pixel, at which the shading cost over no SAA is read (the nearest "
      "measured count not above it: 1, 4 or 16); default {}",
      kMaxLights, default_text);
}

// A value as it may be shown in a one-line message: printable ASCII, at most 40 characters.
std::string show(std::string_view text, std::size_t limit = 40) {
  std::string shown;
  for (char c : text.substr(0, limit)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f && c != '\\')
      shown += c;
    else
      shown += fmt::format("\\x{:02x}", byte);
  }
  if (text.size() > limit) shown += "...";
  return shown;
}

std::string quoted_list(const std::vector<std::string>& values) {
  std::vector<std::string> quoted;
  for (const std::string& value : values) quoted.push_back("\"" + value + "\"");
  return fmt::format("{}", fmt::join(quoted, ", "));
}

std::string_view type_phrase(toml::node_type type) {
  switch (type) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

SourcePosition position_of(const toml::source_region& region) {
  return {static_cast<int>(region.begin.line), static_cast<int>(region.begin.column)};
}

bool is_identifier(std::string_view text, bool allow_dash) {
  if (text.empty() || text.size() > 64 || !std::isalpha(static_cast<unsigned char>(text[0]))) return false;
  return std::all_of(text.begin(), text.end(),
                     [&](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (allow_dash && c == '-'); });
}

// Reads one table's keys, in file order, checking each against the allowed set and its type.
class TableReader {
 public:
  TableReader(const Manifest& manifest, const toml::table& table, std::string context, const std::vector<std::string>& allowed)
      : manifest_(manifest), table_(table), context_(std::move(context)) {
    std::vector<std::pair<SourcePosition, std::string>> keys;
    for (auto&& [key, node] : table) keys.emplace_back(position_of(key.source()), std::string(key.str()));
    std::sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) {
      return std::tie(a.first.line, a.first.column, a.second) < std::tie(b.first.line, b.first.column, b.second);
    });
    for (const auto& [position, key] : keys) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        fail(position, fmt::format("unknown key '{}'{}; allowed keys: {}", show(key), context_, fmt::join(allowed, ", ")));
      }
    }
  }

  const toml::node* find(std::string_view key) const { return table_.get(key); }
  bool has(std::string_view key) const { return find(key) != nullptr; }

  SourcePosition position(std::string_view key) const {
    const toml::node* node = find(key);
    return node ? position_of(node->source()) : position_of(table_.source());
  }

  [[noreturn]] void fail(SourcePosition position, const std::string& message) const { throw Error(manifest_.where(position) + message); }
  [[noreturn]] void fail_key(std::string_view key, const std::string& problem, const std::string& allowed) const {
    fail(position(key), fmt::format("key '{}'{}: {}; allowed: {}", key, context_, problem, allowed));
  }
  [[noreturn]] void missing(std::string_view key, const std::string& allowed) const {
    fail(position_of(table_.source()), fmt::format("missing key '{}'{}; allowed: {}", key, context_, allowed));
  }
  [[noreturn]] void wrong_type(std::string_view key, const toml::node& node, const std::string& allowed) const {
    fail(position_of(node.source()), fmt::format("key '{}'{}: must be {}, got {}; allowed: {}", key, context_, allowed_type_of(allowed),
                                                 type_phrase(node.type()), allowed));
  }

  std::optional<std::string> string(std::string_view key, const std::string& allowed) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_string()) wrong_type(key, *node, allowed);
    return std::string(node->as_string()->get());
  }

  // One of `values` (strings).
  std::optional<std::string> choice(std::string_view key, const std::vector<std::string>& values) const {
    const std::string allowed = quoted_list(values);
    const auto value = string(key, allowed);
    if (value && std::find(values.begin(), values.end(), *value) == values.end()) {
      fail_key(key, fmt::format("unknown value \"{}\"", show(*value)), allowed);
    }
    return value;
  }

  std::optional<bool> boolean(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_boolean()) wrong_type(key, *node, "true, false");
    return node->as_boolean()->get();
  }

  // An integer in [low, high]: a floating-point value (4.0 included) is the wrong type.
  std::optional<int> integer(std::string_view key, int low, int high, const std::string& allowed) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_integer()) wrong_type(key, *node, allowed);
    const std::int64_t value = node->as_integer()->get();
    if (value < low || value > high) fail_key(key, fmt::format("{} is outside [{}, {}]", value, low, high), allowed);
    return static_cast<int>(value);
  }

  std::optional<double> number(std::string_view key, const std::string& allowed) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (node->is_integer()) return static_cast<double>(node->as_integer()->get());
    if (!node->is_floating_point()) wrong_type(key, *node, allowed);
    return node->as_floating_point()->get();
  }

  const std::string& context() const { return context_; }

 private:
  static std::string allowed_type_of(const std::string& allowed) {
    if (allowed == "true, false") return "a boolean";
    if (allowed.rfind("a number", 0) == 0) return "a number";
    if (allowed.rfind("an integer", 0) == 0) return "an integer";
    if (allowed.rfind("an array of tables", 0) == 0) return "an array of tables";
    if (allowed.rfind("an array", 0) == 0) return "an array";
    return "a string";
  }

  const Manifest& manifest_;
  const toml::table& table_;
  std::string context_;
};

// The manifest precisions every target can emit: fp32 always, fp16 when each target has a
// half-precision form (see target_precision).
std::vector<Precision> precisions_of_all(const std::vector<OutputTarget>& targets) {
  std::vector<Precision> common = {Precision::fp32};
  const bool half = std::all_of(targets.begin(), targets.end(),
                                [](const OutputTarget& target) { return target_precision(target, Precision::fp16).has_value(); });
  if (half) common.push_back(Precision::fp16);
  return common;
}

void read_targets(Manifest& manifest, const TableReader& top) {
  const std::vector<std::string> names = builtin_target_names();
  const std::string allowed = "an array of " + quoted_list(names);
  const toml::node* node = top.find("targets");
  if (!node) top.missing("targets", allowed);
  if (!node->is_array()) top.wrong_type("targets", *node, allowed);
  const toml::array& array = *node->as_array();
  if (array.empty()) top.fail_key("targets", "the array is empty", allowed);
  for (const toml::node& element : array) {
    const SourcePosition position = position_of(element.source());
    if (!element.is_string()) {
      top.fail(position, fmt::format("key 'targets': every element must be a string, got {}; allowed: {}", type_phrase(element.type()),
                                     quoted_list(names)));
    }
    const std::string name(element.as_string()->get());
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      top.fail(position, fmt::format("key 'targets': unknown target \"{}\"; allowed: {}", show(name), quoted_list(names)));
    }
    const OutputTarget target = OutputTarget::snippet(name);
    if (std::find(manifest.targets.begin(), manifest.targets.end(), target) != manifest.targets.end()) {
      top.fail(position, fmt::format("key 'targets': \"{}\" is listed twice; allowed: each of {} at most once", name, quoted_list(names)));
    }
    manifest.targets.push_back(target);
  }
}

// The emission options of `catalogue` and of the glint catalogue (glint_count, ...: they apply to
// the materials with glints = true; check_glint_options refuses them without one).
void read_options(Manifest& manifest, const TableReader& top, const Catalogue& catalogue) {
  std::vector<Constant> constants = catalogue.constants();
  for (const Constant& constant : glints::catalogue().constants()) {
    if (!constant.option.empty() && !catalogue.find_option(constant.option)) constants.push_back(constant);
  }
  for (const Constant& constant : constants) {
    if (constant.option.empty()) continue;
    const std::string allowed =
        fmt::format("a number in {} ({}; default {})", constant.range->describe(), constant.meaning, constant.value);
    const auto value = top.number(constant.option, allowed);
    if (!value) continue;
    if (!std::isfinite(*value) || !constant.range->contains(*value)) {
      top.fail_key(constant.option, fmt::format("{} is out of range", *value), allowed);
    }
    manifest.option_values[constant.option] = *value;
  }
}

void check_glint_options(const Manifest& manifest, const TableReader& top, const Catalogue& catalogue) {
  if (plans_glints(manifest)) return;
  for (const auto& [option, value] : manifest.option_values) {
    if (!catalogue.find_option(option)) {
      top.fail_key(option, "a glint option, and no material has glints = true", "the key with a material that sets glints = true");
    }
  }
}

// A value the file sets that a material's precision would emit as 0 (below the smallest normal
// number) is named at its key, file:line:column, not as a command-line option it never was.
void check_options_representable(const Manifest& manifest, const TableReader& top) {
  const bool half = std::any_of(manifest.materials.begin(), manifest.materials.end(),
                                [](const Material& material) { return is_half(material.precision); });
  const double smallest_normal = half ? 0x1.0p-14 : static_cast<double>(std::numeric_limits<float>::min());
  const std::string_view precision = to_string(half ? Precision::fp16 : Precision::fp32);
  for (const auto& [option, value] : manifest.option_values) {
    if (!top.has(option) || value == 0.0 || std::fabs(value) >= smallest_normal) continue;
    top.fail_key(option, fmt::format("{} is below the smallest normal {} number and would be emitted as 0", value, precision),
                 fmt::format("a number of at least {:g} (with {} materials)", smallest_normal, precision));
  }
}

// `preset` and `domain` (saagen/emit/engines.hpp): the preset's constants fill the options the file
// does not set; `domain` defaults to the preset's.
void read_engine_settings(Manifest& manifest, const TableReader& top) {
  std::vector<std::string> preset_names, domain_names;
  for (const Preset& preset : presets()) preset_names.push_back(preset.id);
  for (const RoughnessDomain& domain : roughness_domains()) domain_names.push_back(domain.id);
  manifest.preset = top.choice("preset", preset_names);
  if (manifest.preset) {
    const Preset& preset = find_preset(*manifest.preset);
    manifest.option_values.emplace("sigma2", preset.sigma2);
    manifest.option_values.emplace("kappa", preset.kappa);
    manifest.domain = preset.domain;
  }
  if (const auto domain = top.choice("domain", domain_names)) manifest.domain = find_domain(*domain).kind;
}

// A preset's variant serves the deferred materials that name none.
void apply_preset_variant(Manifest& manifest, const Catalogue& catalogue) {
  if (!manifest.preset) return;
  const Preset& preset = find_preset(*manifest.preset);
  if (!catalogue.find_variant(preset.variant)) return;
  for (Material& material : manifest.materials) {
    if (!material.variant && material.path == RenderPath::deferred) material.variant = preset.variant;
  }
}

// `roughness`: a number in [0, 1], or an array [lowest, highest] of two (lowest <= highest).
std::optional<RoughnessRange> read_roughness(const TableReader& reader) {
  const std::string rule =
      "a number in [0, 1], the perceptual roughness (as glTF's roughnessFactor; GGX alpha is its square), or [lowest, highest] where a "
      "texture varies it";
  const toml::node* node = reader.find("roughness");
  if (!node) return std::nullopt;
  const auto value_of = [&](const toml::node& element) {
    if (!element.is_number()) reader.wrong_type("roughness", element, rule);
    const double value = element.is_integer() ? static_cast<double>(element.as_integer()->get()) : element.as_floating_point()->get();
    if (!(value >= 0.0 && value <= 1.0)) reader.fail_key("roughness", fmt::format("{} is outside [0, 1]", value), rule);
    return value;
  };
  if (!node->is_array()) {
    const double value = value_of(*node);
    return RoughnessRange{value, value};
  }
  const toml::array& range = *node->as_array();
  if (range.size() != 2) reader.fail_key("roughness", fmt::format("an array of {} numbers", range.size()), rule);
  const RoughnessRange roughness{value_of(range[0]), value_of(range[1])};
  if (roughness.low > roughness.high)
    reader.fail_key("roughness", fmt::format("the lowest, {}, is above the highest, {}", roughness.low, roughness.high), rule);
  return roughness;
}

// A material's name (an identifier, required), source note and render path (required).
void read_identity(const TableReader& reader, Material& material) {
  const std::string name_rule = "an identifier: a letter, then letters, digits, '_' or '-' (at most 64 characters)";
  const auto name = reader.string("name", name_rule);
  if (!name) reader.missing("name", name_rule);
  if (!is_identifier(*name, true)) reader.fail_key("name", fmt::format("\"{}\" is not an identifier", show(*name)), name_rule);
  material.name = *name;
  reader.string("source", kSourceRule);  // a note for the reader (e.g. the glTF material it was written from)

  const auto path = reader.choice("path", {"forward", "deferred"});
  if (!path) reader.missing("path", "\"forward\", \"deferred\"");
  material.path = *path == "forward" ? RenderPath::forward : RenderPath::deferred;
}

// What the material's surface is: anisotropy, tangents, NDF, normal maps, content, glints and
// the precision it is shaded at, each checked against the keys read before it.
void read_surface(const TableReader& reader, const std::vector<Precision>& precisions, Material& material) {
  material.anisotropic = reader.boolean("anisotropic").value_or(false);
  material.tangents = reader.boolean("tangents").value_or(false);
  if (const auto ndf = reader.choice("ndf", {"ggx", "beckmann"})) material.ndf = *ndf == "ggx" ? Ndf::ggx : Ndf::beckmann;
  material.normal_maps = reader.boolean("normal_maps").value_or(false);
  const std::vector<std::string> contents(advice::kContentNames.begin(), advice::kContentNames.end());
  if (const auto content = reader.choice("content", contents)) {
    material.content = advice::content_named(*content);
    if (material.content == advice::Content::normal_mapped && !material.normal_maps)
      reader.fail_key("content", "\"normal-mapped\" needs normal_maps = true", "normal_maps = true, or another content type");
  }
  material.glints = reader.boolean("glints").value_or(false);
  if (material.glints && (material.path != RenderPath::forward || !material.tangents)) {
    reader.fail_key(
        "glints", "the glinty BRDF is evaluated per light in the tangent frame: glints = true needs path = \"forward\" and tangents = true",
        "false, or true with path = \"forward\" and tangents = true");
  }
  if (const auto precision = reader.choice("precision", precision_names(precisions))) material.precision = parse_precision(*precision);
  if (material.glints && is_half(material.precision)) {
    reader.fail_key("precision",
                    "the glinty BRDF is numerically supported in fp32 only (no half-precision error bound is derived or proven)",
                    "\"fp32\" with glints = true");
  }
}

// What the plan may spend and where it is read: prefer, budget, lights, the normal maps' closest
// MIP level and the roughness.
void read_trade(const Manifest& manifest, const TableReader& reader, Material& material) {
  if (const auto prefer = reader.choice("prefer", {"accuracy", "speed"})) {
    material.prefer = *prefer == "accuracy" ? Preference::accuracy : Preference::speed;
  }
  const std::string budget_rule = "a number from 1 to 16: the most shading cost over no SAA the material may spend (1.25: 25 % more)";
  if (const auto budget = reader.number("budget", budget_rule)) {
    if (!(*budget >= 1.0 && *budget <= 16.0)) reader.fail_key("budget", fmt::format("{} is outside [1, 16]", *budget), budget_rule);
    material.budget = *budget;
  }
  material.lights = reader.integer("lights", 1, kMaxLights, lights_rule("the scene's `lights`, else 1")).value_or(manifest.lights);
  const std::string map_lod_rule = fmt::format(
      "an integer from 0 to {}: the finest MIP level the material's normal maps are sampled at where it is seen closest (default 0: "
      "close-ups)",
      kMaxMapLod);
  if (const auto map_lod = reader.integer("map_lod", 0, kMaxMapLod, map_lod_rule)) {
    if (!material.normal_maps) reader.fail_key("map_lod", "a normal map's distance needs normal_maps = true", "normal_maps = true");
    material.map_lod = *map_lod;
  }
  material.roughness = read_roughness(reader);
}

// The filter variant the manifest names (`variant`), if any: a screen-space filter that reads no
// resource (the glint variant is planned through `glints = true`).
void read_named_variant(const TableReader& reader, const Catalogue& catalogue, Material& material) {
  std::vector<std::string> filters;
  for (const Variant& variant : catalogue.variants()) {
    const bool reads_resource = !resources_read(catalogue, variant.functions).empty();
    if (is_screen_space_filter(catalogue, variant) && !reads_resource) filters.push_back(variant.id);
  }
  const auto variant = reader.string("variant", quoted_list(filters));
  if (!variant) return;
  if (std::find(filters.begin(), filters.end(), *variant) == filters.end()) {
    const bool is_brdf = catalogue.find_variant(*variant) != nullptr;
    reader.fail_key(
        "variant",
        fmt::format("{} \"{}\"", is_brdf ? "not a filter variant (the BRDF is planned from 'ndf'):" : "unknown variant", show(*variant)),
        quoted_list(filters));
  }
  if (material.glints)
    reader.fail_key("variant", "glints = true picks the glint variant; leave 'variant' out", "no 'variant' with glints = true");
  material.variant = *variant;
}

Material read_material(const Manifest& manifest, const toml::table& table, std::size_t index, const std::vector<Precision>& precisions,
                       const Catalogue& catalogue) {
  Material material;
  material.position = position_of(table.source());
  // The context names the material by its name once it is known to be a safe identifier.
  std::string context = fmt::format(" of material #{}", index + 1);
  if (const toml::node* name = table.get("name"); name && name->is_string() && is_identifier(name->as_string()->get(), true)) {
    context = fmt::format(" of material '{}'", name->as_string()->get());
  }
  const TableReader reader(manifest, table, context, material_keys());
  read_identity(reader, material);
  read_surface(reader, precisions, material);
  read_trade(manifest, reader, material);
  read_named_variant(reader, catalogue, material);
  for (auto&& [key, node] : table) material.positions[std::string(key.str())] = position_of(node.source());
  return material;
}

void read_materials(Manifest& manifest, const TableReader& top, const Catalogue& catalogue) {
  const std::string allowed = "an array of tables, one [[material]] per material";
  const toml::node* node = top.find("material");
  if (!node) top.missing("material", allowed);
  if (!node->is_array()) top.wrong_type("material", *node, allowed);
  const toml::array& array = *node->as_array();
  if (array.empty()) top.fail_key("material", "the array is empty", allowed);
  const auto precisions = precisions_of_all(manifest.targets);
  std::map<std::string, SourcePosition> first_seen;
  for (std::size_t index = 0; index < array.size(); ++index) {
    const toml::node& element = *array.get(index);
    if (!element.is_table()) {
      top.fail(position_of(element.source()), fmt::format("key 'material': element #{} must be a table, got {}; allowed: {}", index + 1,
                                                          type_phrase(element.type()), allowed));
    }
    Material material = read_material(manifest, *element.as_table(), index, precisions, catalogue);
    const SourcePosition name_position = material.positions.at("name");
    if (const auto seen = first_seen.find(material.name); seen != first_seen.end()) {
      top.fail(name_position, fmt::format("key 'name' of material #{}: duplicate material name \"{}\" (first defined at {}:{}:{}); "
                                          "allowed: a name no other material has",
                                          index + 1, material.name, manifest.source_name, seen->second.line, seen->second.column));
    }
    first_seen[material.name] = name_position;
    manifest.materials.push_back(std::move(material));
  }
}

// How deep a manifest may nest: dotted-key parts plus the arrays and inline tables around them.
// A scene manifest needs 2; toml++ recurses once per level and overflows the stack on deep input.
constexpr int nesting_limit = 32;

// What the pre-parse scan found: where, and the message's text after the position.
struct TextProblem {
  SourcePosition position;
  std::string message;
};

// Scans TOML text before toml++ parses it, for what toml++ 3.3 cannot take safely:
// - nesting deeper than nesting_limit (dots are counted in keys, i.e. table headers, before '=' and
//   inside inline tables; brackets in values; strings and comments are skipped);
// - non-ASCII characters outside comments: toml++ 3.3 classifies them as whitespace through an
//   unreachable branch (undefined behaviour) in keys, in bare values (which may swallow quotes)
//   and in multi-line strings. TOML's bare keys and every value saagen accepts are ASCII, so no
//   valid manifest is lost.
class ManifestScanner {
 public:
  explicit ManifestScanner(std::string_view text) : text_(text) {}

  std::optional<TextProblem> first_problem() {
    bool line_start = true;
    for (at_ = 0; at_ < text_.size() && !problem_; ++at_) {
      const char c = text_[at_];
      if (c == '\n') {
        newline();
        line_start = true;
        continue;
      }
      if (c == ' ' || c == '\t' || c == '\r') continue;
      if (line_start && containers_.empty()) start_line(c);
      line_start = false;
      if (c == '#')
        skip_comment();
      else if (c == '"' || c == '\'')
        skip_string(c);
      else if (static_cast<unsigned char>(c) >= 0x80)
        non_ascii();
      else if (!step(c))
        report(
            fmt::format("nested deeper than {} levels (dotted keys, arrays or inline tables); allowed: at most {} "
                        "(a scene manifest needs 2)",
                        nesting_limit, nesting_limit));
    }
    return problem_;
  }

 private:
  void start_line(char first) {
    in_key_ = true;
    key_dots_ = 0;
    header_ = first == '[';
  }

  // One structural character; false when it nests too deeply.
  bool step(char c) {
    if (header_) {
      if (c == ']')
        in_key_ = false;
      else if (c == '.' && in_key_)
        ++key_dots_;
      return depth() <= nesting_limit;
    }
    if (in_key_) {
      if (c == '=')
        in_key_ = false;
      else if (c == '.')
        ++key_dots_;
      else if (c == '}' && !containers_.empty())
        containers_.pop_back();  // `{}` or a trailing `}`
      return depth() <= nesting_limit;
    }
    if (c == '[' || c == '{') {
      containers_.push_back({c, key_dots_});
      in_key_ = c == '{';
      key_dots_ = 0;
    } else if ((c == ']' || c == '}') && !containers_.empty()) {
      key_dots_ = containers_.back().outer_dots;
      containers_.pop_back();
    } else if (c == ',' && !containers_.empty() && containers_.back().bracket == '{') {
      in_key_ = true;
      key_dots_ = 0;
    }
    return depth() <= nesting_limit;
  }

  int depth() const {
    int outer = 0;
    for (const Container& container : containers_) outer += container.outer_dots + 1;
    return outer + key_dots_ + 1;
  }

  void non_ascii() {
    report(fmt::format(
        "non-ASCII byte 0x{:02x} outside a comment; allowed: ASCII keys and values (every name and value saagen reads is ASCII)",
        static_cast<unsigned char>(text_[at_])));
  }

  void report(std::string message) {
    if (!problem_) problem_ = TextProblem{position(), std::move(message)};
  }

  void newline() {
    ++line_;
    line_at_ = at_ + 1;
  }

  void skip_comment() {
    while (at_ + 1 < text_.size() && text_[at_ + 1] != '\n') ++at_;
  }

  // From the opening quote to the closing one (""" and ''' strings span lines); strings must be
  // ASCII too.
  void skip_string(char quote) {
    const bool triple = text_.substr(at_, 3) == std::string(3, quote);
    at_ += triple ? 3 : 1;
    for (; at_ < text_.size(); ++at_) {
      const char c = text_[at_];
      if (static_cast<unsigned char>(c) >= 0x80) return non_ascii();
      if (c == '\\' && quote == '"') {
        ++at_;
        if (at_ < text_.size() && text_[at_] == '\n')
          newline();
        else if (at_ < text_.size() && static_cast<unsigned char>(text_[at_]) >= 0x80)
          return non_ascii();
      } else if (c == '\n') {
        newline();
        if (!triple) return;
      } else if (c == quote && (!triple || text_.substr(at_, 3) == std::string(3, quote))) {
        if (triple) at_ += 2;
        return;
      }
    }
  }

  SourcePosition position() const { return {line_, static_cast<int>(at_ - line_at_) + 1}; }

  struct Container {
    char bracket;
    int outer_dots;  // the dots of the key this container is the value of
  };
  std::string_view text_;
  std::size_t at_ = 0;
  std::size_t line_at_ = 0;
  int line_ = 1;
  bool in_key_ = true;
  bool header_ = false;
  int key_dots_ = 0;
  std::vector<Container> containers_;
  std::optional<TextProblem> problem_;
};

// Size, nesting and characters are checked before toml++ sees the text (see ManifestScanner).
void check_manifest_limits(const Manifest& manifest, std::string_view text) {
  if (text.size() > manifest_size_limit) {
    throw Error(manifest.where({1, 1}) + fmt::format("the manifest is larger than {} KiB; allowed: a scene manifest of at most {} KiB",
                                                     manifest_size_limit >> 10, manifest_size_limit >> 10));
  }
  if (const auto problem = ManifestScanner(text).first_problem()) throw Error(manifest.where(problem->position) + problem->message);
}

}  // namespace

std::optional<AlphaRange> alpha_range(const Material& material) {
  if (!material.roughness) return std::nullopt;
  return AlphaRange{material.roughness->low * material.roughness->low, material.roughness->high * material.roughness->high};
}

advice::Content content_of(const Material& material) {
  if (material.content) return *material.content;
  return material.normal_maps ? advice::Content::normal_mapped : advice::Content::curved;
}

std::optional<Precision> target_precision(const OutputTarget& target, Precision precision) {
  const auto& precisions = builtin_target(target.table).precisions;
  if (precisions.count(precision)) return precision;
  if (precision == Precision::fp16 && precisions.count(Precision::min16)) return Precision::min16;
  return std::nullopt;
}

std::string_view to_string(Preference preference) { return preference == Preference::accuracy ? "accuracy" : "speed"; }
std::string_view to_string(Ndf ndf) { return ndf == Ndf::ggx ? "ggx" : "beckmann"; }

std::string Manifest::where(SourcePosition position) const {
  return fmt::format("{}:{}:{}: ", source_name, std::max(position.line, 1), std::max(position.column, 1));
}

const std::vector<std::string>& manifest_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> names = {"name", "targets", "prefix", "gpu_family", "lights"};
    for (const Constant& constant : glints::catalogue().constants()) {  // the SAA options, then the glint options
      if (!constant.option.empty()) names.push_back(constant.option);
    }
    names.insert(names.end(), {"preset", "domain", "import_path", "taa", "source", "material"});
    return names;
  }();
  return keys;
}

const std::vector<std::string>& material_keys() {
  static const std::vector<std::string> keys = {"name",    "path",      "anisotropic", "tangents", "ndf",    "normal_maps",
                                                "content", "glints",    "precision",   "prefer",   "budget", "lights",
                                                "map_lod", "roughness", "variant",     "source"};
  return keys;
}

Manifest parse_manifest(std::string_view text, std::string_view source_name, const Catalogue& catalogue) {
  Manifest manifest;
  manifest.source_name = std::string(source_name);
  check_manifest_limits(manifest, text);
  toml::table document;
  try {
    document = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& error) {
    throw Error(manifest.where(position_of(error.source())) +
                fmt::format("not valid TOML: {}; allowed: TOML 1.0 (see examples/scene.saagen.toml)", show(error.description(), 200)));
  }

  const TableReader top(manifest, document, "", manifest_keys());
  read_targets(manifest, top);
  top.string("source", kSourceRule);  // a note for the reader (e.g. the asset plan --gltf read), not planned

  const std::string prefix_rule = "letters, digits and '_', starting with a letter, at most 32 characters, no '__', not 'gl_'";
  if (const auto prefix = top.string("prefix", prefix_rule)) {
    try {
      validate_prefix(*prefix);
    } catch (const Error&) {
      top.fail_key("prefix", fmt::format("\"{}\" is not a safe identifier prefix", show(*prefix)), prefix_rule);
    }
    manifest.prefix = *prefix;
  }

  const std::string name_rule = "an identifier: a letter, then letters, digits or '_' (at most 64 characters); default \"scene\"";
  if (const auto name = top.string("name", name_rule)) {
    if (!is_identifier(*name, false)) top.fail_key("name", fmt::format("\"{}\" is not an identifier", show(*name)), name_rule);
    for (const Variant& variant : catalogue.variants()) {
      std::string stem = variant.id;
      std::replace(stem.begin(), stem.end(), '-', '_');
      if (stem == *name) {
        top.fail_key("name", fmt::format("\"{}\" would collide with the file `saagen emit` writes for {}", *name, variant.id), name_rule);
      }
    }
    manifest.name = *name;
  }

  if (const auto family = top.choice("gpu_family", committed_isa_costs().families)) manifest.gpu_family = *family;
  manifest.lights = top.integer("lights", 1, kMaxLights, lights_rule("1")).value_or(1);
  const std::string import_rule = "identifiers joined by '::' (e.g. \"saagen::scene\"), for a module target (wgsl) in targets";
  if (const auto path = top.string("import_path", import_rule)) {
    try {
      validate_import_path(*path);
    } catch (const Error&) {
      top.fail_key("import_path", fmt::format("\"{}\" is not a module path", show(*path)), import_rule);
    }
    const bool module_target = std::any_of(manifest.targets.begin(), manifest.targets.end(),
                                           [](const OutputTarget& target) { return builtin_target(target.table).takes_import_path(); });
    if (!module_target) top.fail_key("import_path", "no target in targets is a module language", import_rule);
    manifest.import_path = *path;
  }
  manifest.taa = top.boolean("taa").value_or(false);
  read_options(manifest, top, catalogue);
  read_engine_settings(manifest, top);
  read_materials(manifest, top, catalogue);
  check_glint_options(manifest, top, catalogue);
  check_options_representable(manifest, top);
  apply_preset_variant(manifest, catalogue);
  return manifest;
}

Manifest load_manifest(const std::filesystem::path& path, const Catalogue& catalogue) {
  const std::string text = read_input_file(path, manifest_size_limit, "a scene manifest (see examples/scene.saagen.toml)");
  return parse_manifest(text, path.string(), catalogue);
}

std::string glint_dictionary_file_name(const Manifest& manifest) { return manifest.prefix + manifest.name + "_glint_dictionary.ktx2"; }

bool plans_glints(const Manifest& manifest) {
  return std::any_of(manifest.materials.begin(), manifest.materials.end(), [](const Material& material) { return material.glints; });
}

}  // namespace saagen
