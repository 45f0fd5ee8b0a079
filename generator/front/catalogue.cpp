#include "saagen/front/catalogue.hpp"

#include "saagen/advice.hpp"
#include "saagen/error.hpp"
#include "saagen/front/dialect.hpp"
#include "saagen/front/syntax_tree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <functional>
#include <set>
#include <sstream>

namespace saagen {
namespace embedded {
const std::map<std::string, std::string_view>& files();
}

namespace {

struct Line {
  std::string_view text;
  int number;
};

[[noreturn]] void fail(const std::string& file, int line, const std::string& message) {
  throw Error(fmt::format("{}:{}: {}", file, line, message));
}

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_words(std::string_view text) {
  std::vector<std::string> words;
  std::istringstream stream{std::string(text)};
  for (std::string word; stream >> word;) words.push_back(word);
  return words;
}

bool contains(const std::vector<std::string>& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool is_identifier(std::string_view text) {
  if (text.empty() || !(std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_')) return false;
  return std::all_of(text.begin(), text.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::optional<double> parse_number(std::string_view text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// Splits "TYPE NAME | meaning" or "TYPE | meaning" into the words before '|' and the meaning.
std::pair<std::vector<std::string>, std::string> split_declaration(std::string_view value) {
  const auto bar = value.find('|');
  if (bar == std::string_view::npos) return {split_words(value), std::string()};
  return {split_words(value.substr(0, bar)), std::string(trim(value.substr(bar + 1)))};
}

class TemplateParser {
 public:
  TemplateParser(const TemplateSource& source, std::vector<Variant>& variants, std::vector<Function>& functions,
                 std::vector<Constant>& constants)
      : file_(source.name), variants_(variants), functions_(functions), constants_(constants) {
    std::string_view text = source.text;
    int number = 1;
    for (std::size_t begin = 0; begin <= text.size();) {
      auto end = text.find('\n', begin);
      if (end == std::string_view::npos) end = text.size();
      lines_.push_back({text.substr(begin, end - begin), number++});
      begin = end + 1;
    }
  }

  void parse() {
    check_ascii();
    while (next_ < lines_.size()) {
      const Line& line = lines_[next_];
      const std::string_view text = trim(line.text);
      if (text.empty() || text.front() == '#') {
        ++next_;
        continue;
      }
      const auto words = split_words(text);
      if (words.size() != 2 || words[0].front() != '@') {
        fail(file_, line.number, fmt::format("expected '@variant ID', '@function NAME' or '@constant NAME', found '{}'", text));
      }
      ++next_;
      if (words[0] == "@variant")
        parse_variant(words[1], line.number);
      else if (words[0] == "@function")
        parse_function(words[1], line.number);
      else if (words[0] == "@constant")
        parse_constant(words[1], line.number);
      else
        fail(file_, line.number, fmt::format("unknown block '{}'; use @variant, @function or @constant", words[0]));
    }
  }

 private:
  void check_ascii() const {
    for (const Line& line : lines_) {
      for (char c : line.text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte > 127) fail(file_, line.number, "non-ASCII character; templates (and the code they emit) must be ASCII");
        if (byte < 0x20 || byte == 0x7f) {
          fail(file_, line.number,
               fmt::format("control character 0x{:02x}; templates (and the code they emit) are printable ASCII, "
                           "indented with spaces",
                           byte));
        }
      }
    }
  }

  // Reads "key: value" lines until a blank line, a new block or a body.
  std::vector<std::pair<std::string, Line>> read_properties() {
    std::vector<std::pair<std::string, Line>> properties;
    while (next_ < lines_.size()) {
      const Line& line = lines_[next_];
      const std::string_view text = trim(line.text);
      if (text.empty() || text.front() == '@' || text == "{") break;
      if (text.front() == '#') {
        ++next_;
        continue;
      }
      const auto colon = text.find(':');
      if (colon == std::string_view::npos) fail(file_, line.number, fmt::format("expected 'key: value', found '{}'", text));
      properties.push_back({std::string(trim(text.substr(0, colon))), Line{trim(text.substr(colon + 1)), line.number}});
      ++next_;
    }
    return properties;
  }

  static void require_keys(const std::string& file, int line, std::string_view block, const std::set<std::string>& present,
                           const std::vector<std::string>& required) {
    for (const std::string& key : required) {
      if (!present.count(key)) fail(file, line, fmt::format("{} is missing the '{}:' line", block, key));
    }
  }

  void parse_variant(const std::string& id, int line) {
    // A variant id is a CLI argument, a manifest value and a marker list item (comma-separated):
    // letters, digits and '-' only, starting with a letter.
    const bool valid_id = !id.empty() && std::isalpha(static_cast<unsigned char>(id[0])) &&
                          std::all_of(id.begin(), id.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-'; });
    if (!valid_id) fail(file_, line, fmt::format("variant id '{}' must be letters, digits and '-', starting with a letter", id));
    Variant variant;
    variant.id = id;
    variant.source_file = file_;
    variant.line = line;
    std::set<std::string> seen;
    for (const auto& [key, value] : read_properties()) {
      if (!seen.insert(key).second) fail(file_, value.number, fmt::format("duplicate key '{}'", key));
      const std::string text(value.text);
      if (key == "summary")
        variant.summary = text;
      else if (key == "paper")
        variant.paper = text;
      else if (key == "equation")
        variant.equation = text;
      else if (key == "domain")
        variant.domain = text;
      else if (key == "functions")
        variant.functions = split_words(text);
      else if (key == "path")
        variant.path = parse_path(text, value.number);
      else if (key == "tangents")
        variant.needs_tangents = parse_yes_no(text, value.number);
      else if (key == "precisions")
        variant.precisions = parse_precisions(text, value.number);
      else
        fail(
            file_, value.number,
            fmt::format("unknown variant key '{}'; allowed: summary, paper, equation, path, tangents, domain, functions, precisions", key));
    }
    require_keys(file_, line, "@variant " + id, seen, {"summary", "paper", "equation", "path", "tangents", "domain", "functions"});
    variants_.push_back(std::move(variant));
  }

  RenderPath parse_path(const std::string& text, int line) const {
    if (text == "forward") return RenderPath::forward;
    if (text == "deferred") return RenderPath::deferred;
    if (text == "any") return RenderPath::any;
    fail(file_, line, fmt::format("path '{}' is not one of forward, deferred, any", text));
  }

  std::vector<Precision> parse_precisions(const std::string& text, int line) const {
    std::vector<Precision> precisions;
    for (const std::string& word : split_words(text)) {
      const auto precision = precision_named(word);
      if (!precision) fail(file_, line, fmt::format("precision '{}' is not one of {}", word, precision_id_list()));
      precisions.push_back(*precision);
    }
    return precisions;
  }

  bool parse_yes_no(const std::string& text, int line) const {
    if (text == "yes") return true;
    if (text == "no") return false;
    fail(file_, line, fmt::format("'{}' is not yes or no", text));
  }

  void parse_function(const std::string& name, int line) {
    if (!is_identifier(name)) fail(file_, line, fmt::format("'{}' is not an identifier", name));
    Function function;
    function.name = name;
    function.source_file = file_;
    function.line = line;
    std::set<std::string> seen;
    for (const auto& [key, value] : read_properties()) {
      if (key != "param" && !seen.insert(key).second) fail(file_, value.number, fmt::format("duplicate key '{}'", key));
      seen.insert(key);
      if (key == "role")
        function.role = parse_role(std::string(value.text), value.number);
      else if (key == "cite")
        function.cite = std::string(value.text);
      else if (key == "returns")
        parse_returns(function, value);
      else if (key == "param")
        function.parameters.push_back(parse_parameter(value));
      else
        fail(file_, value.number, fmt::format("unknown function key '{}'; allowed: role, cite, returns, param", key));
    }
    require_keys(file_, line, "@function " + name, seen, {"role", "cite", "returns"});
    function.body_line = next_ < lines_.size() ? lines_[next_].number + 1 : line;
    function.body = read_body(name, line);
    functions_.push_back(std::move(function));
  }

  FunctionRole parse_role(const std::string& text, int line) const {
    if (text == "core") return FunctionRole::core;
    if (text == "fragment") return FunctionRole::fragment;
    if (text == "evaluate") return FunctionRole::evaluate;
    if (text == "helper") return FunctionRole::helper;
    fail(file_, line, fmt::format("role '{}' is not one of core, fragment, evaluate, helper", text));
  }

  void check_type(const std::string& type, int line) const {
    if (!contains(dialect::type_names(), type)) {
      fail(file_, line, fmt::format("unknown type '{}'; the dialect has real, real2, real3, real4, bool, int (no matrices)", type));
    }
  }

  void parse_returns(Function& function, const Line& value) const {
    auto [words, meaning] = split_declaration(value.text);
    if (words.size() != 1 || meaning.empty()) fail(file_, value.number, "expected 'returns: TYPE | meaning'");
    check_type(words[0], value.number);
    function.return_type = words[0];
    function.return_meaning = meaning;
  }

  Parameter parse_parameter(const Line& value) const {
    auto [words, meaning] = split_declaration(value.text);
    if (words.size() != 2 || meaning.empty()) fail(file_, value.number, "expected 'param: TYPE NAME | meaning'");
    check_type(words[0], value.number);
    if (!is_identifier(words[1])) fail(file_, value.number, fmt::format("'{}' is not an identifier", words[1]));
    return Parameter{words[0], words[1], meaning};
  }

  std::string read_body(const std::string& name, int function_line) {
    if (next_ >= lines_.size() || trim(lines_[next_].text) != "{") {
      fail(file_, function_line, fmt::format("@function {} needs a body: a line '{{', the code, and a line '}}'", name));
    }
    const int open_line = lines_[next_].number;
    ++next_;
    std::string body;
    while (next_ < lines_.size() && lines_[next_].text != "}") {
      body += std::string(lines_[next_].text) + "\n";
      ++next_;
    }
    if (next_ >= lines_.size()) fail(file_, open_line, fmt::format("body of {} has no closing '}}' line at column 1", name));
    ++next_;
    return body;
  }

  void parse_constant(const std::string& name, int line) {
    if (!is_identifier(name)) fail(file_, line, fmt::format("'{}' is not an identifier", name));
    Constant constant;
    constant.name = name;
    constant.source_file = file_;
    constant.line = line;
    std::set<std::string> seen;
    for (const auto& [key, value] : read_properties()) {
      if (!seen.insert(key).second) fail(file_, value.number, fmt::format("duplicate key '{}'", key));
      const std::string text(value.text);
      if (key == "type") {
        check_type(text, value.number);
        constant.type = text;
      } else if (key == "meaning") {
        constant.meaning = text;
      } else if (key == "option") {
        // The option's name is a manifest key, a CLI flag and a marker field (name=value): an
        // identifier, never words.
        if (!is_identifier(text)) fail(file_, value.number, fmt::format("option '{}' is not an identifier", text));
        constant.option = text;
      } else if (key == "value" || key == "default") {
        const auto number = parse_number(text);
        if (!number) fail(file_, value.number, fmt::format("'{}' is not a number", text));
        constant.value = *number;
      } else if (key == "half_value") {
        const auto number = parse_number(text);
        if (!number) fail(file_, value.number, fmt::format("'{}' is not a number", text));
        constant.half_value = *number;
      } else if (key == "range") {
        constant.range = parse_interval(text, value.number);
      } else {
        fail(file_, value.number,
             fmt::format("unknown constant key '{}'; allowed: type, value, half_value, option, default, range, meaning", key));
      }
    }
    require_keys(file_, line, "@constant " + name, seen, {"type", "meaning"});
    const bool is_option = seen.count("option") > 0;
    if (is_option)
      require_keys(file_, line, "@constant " + name, seen, {"default", "range"});
    else
      require_keys(file_, line, "@constant " + name, seen, {"value"});
    if (constant.range && !constant.range->contains(constant.value)) {
      fail(file_, line, fmt::format("default {} of {} is outside its range {}", constant.value, name, constant.range->describe()));
    }
    constants_.push_back(std::move(constant));
  }

  Interval parse_interval(const std::string& text, int line) const {
    const auto comma = text.find(',');
    if (text.size() < 5 || comma == std::string::npos || (text.front() != '(' && text.front() != '[') ||
        (text.back() != ')' && text.back() != ']')) {
      fail(file_, line, fmt::format("range '{}' must look like (0, 4] or [0, 1]", text));
    }
    const auto low = parse_number(trim(std::string_view(text).substr(1, comma - 1)));
    const auto high = parse_number(trim(std::string_view(text).substr(comma + 1, text.size() - comma - 2)));
    if (!low || !high || *low > *high) fail(file_, line, fmt::format("range '{}' needs two ordered numbers", text));
    return Interval{*low, *high, text.front() == '[', text.back() == ']'};
  }

  std::string file_;
  std::vector<Line> lines_;
  std::size_t next_ = 0;
  std::vector<Variant>& variants_;
  std::vector<Function>& functions_;
  std::vector<Constant>& constants_;
};

}  // namespace

std::string_view to_string(FunctionRole role) {
  switch (role) {
    case FunctionRole::core:
      return "core";
    case FunctionRole::fragment:
      return "fragment";
    case FunctionRole::evaluate:
      return "evaluate";
    case FunctionRole::helper:
      return "helper";
  }
  return "helper";
}

std::string_view to_string(RenderPath path) {
  switch (path) {
    case RenderPath::forward:
      return "forward";
    case RenderPath::deferred:
      return "deferred";
    case RenderPath::any:
      return "any";
  }
  return "any";
}

bool Interval::contains(double value) const {
  const bool above = low_inclusive ? value >= low : value > low;
  const bool below = high_inclusive ? value <= high : value < high;
  return above && below;
}

std::string Interval::describe() const {
  return fmt::format("{}{}, {}{}", low_inclusive ? '[' : '(', low, high, high_inclusive ? ']' : ')');
}

Catalogue Catalogue::parse(const std::vector<TemplateSource>& sources) {
  Catalogue catalogue;
  for (const TemplateSource& source : sources) {
    TemplateParser(source, catalogue.variants_, catalogue.functions_, catalogue.constants_).parse();
  }
  catalogue.sources_ = sources;
  catalogue.link();
  return catalogue;
}

Catalogue Catalogue::with_variants(std::vector<Variant> variants) const {
  Catalogue copy = *this;
  copy.variants_ = std::move(variants);
  copy.function_index_.clear();
  copy.link();
  return copy;
}

// The built-in templates' {advice:...} fields: saagen's advice (saagen/advice.hpp), so that the
// emitted headers name the normal, how a prefiltered map is sampled and the default constants the
// planner plans with.
namespace {
std::string with_advice(std::string text) {
  const std::pair<std::string_view, std::string> fields[] = {
      {"{advice:normal}", std::string(advice::kNormalText)},
      {"{advice:prefilter_sampling}", std::string(advice::kPrefilterSamplingText)},
      {"{advice:sigma2}", fmt::format("{}", advice::kSigma2)},
      {"{advice:kappa}", fmt::format("{}", advice::kKappa)},
  };
  for (const auto& [field, value] : fields) {
    for (std::size_t at = text.find(field); at != std::string::npos; at = text.find(field, at + value.size()))
      text.replace(at, field.size(), value);
  }
  return text;
}
}  // namespace

std::vector<TemplateSource> builtin_template_sources() {
  std::vector<TemplateSource> sources;
  for (const auto& [name, text] : embedded::files()) {
    if (name.rfind("templates/", 0) == 0 && name.size() > 4 && name.substr(name.size() - 4) == ".saa") {
      sources.push_back({name, with_advice(std::string(text))});
    }
  }
  return sources;
}

const Catalogue& Catalogue::builtin() {
  static const Catalogue catalogue = parse(builtin_template_sources());
  return catalogue;
}

namespace {

using FunctionIndex = std::map<std::string, std::size_t, std::less<>>;
using ConstantNames = std::set<std::string>;

// Indexes the functions by name and collects the constants' names: no name may be a dialect type,
// an intrinsic or used twice.
ConstantNames index_names(const std::vector<Function>& functions, const std::vector<Constant>& constants, FunctionIndex& index) {
  std::set<std::string, std::less<>> reserved(dialect::type_names().begin(), dialect::type_names().end());
  for (const Function& function : functions) {
    if (reserved.count(function.name) || !index.emplace(function.name, &function - functions.data()).second) {
      fail(function.source_file, function.line, fmt::format("function name '{}' is already used", function.name));
    }
  }
  ConstantNames constant_names;
  for (const Constant& constant : constants) {
    if (index.count(constant.name) || !constant_names.insert(constant.name).second) {
      fail(constant.source_file, constant.line, fmt::format("constant name '{}' is already used", constant.name));
    }
  }
  for (const Function& function : functions) {
    if (dialect::is_intrinsic(function.name)) {
      fail(function.source_file, function.line,
           fmt::format("function name '{}' is a dialect intrinsic; choose another name", function.name));
    }
  }
  return constant_names;
}

// A body naming a matrix type or function, which the dialect does not have.
void refuse_matrices(const Function& function) {
  const auto tokens = dialect::tokenize(function.body);
  for (std::size_t index = 0; index < tokens.size(); ++index) {
    if (tokens[index].kind != dialect::TokenKind::identifier || dialect::is_member_access(tokens, index)) continue;
    const std::string name(tokens[index].text);
    if (contains(dialect::forbidden_names(), name)) {
      fail(function.source_file, function.line,
           fmt::format("{} uses '{}': the dialect has no matrices; write the product with dot products", function.name, name));
    }
  }
}

// Parses and type-checks every body (the typed tree, at load time, with the body's own lines) and
// records each function's direct references: the functions and constants it names, in the
// guarded form and in the paper form, whether it takes derivatives and whether it has guards.
void parse_bodies(std::vector<Function>& functions, const std::vector<Constant>& constants, const FunctionIndex& index,
                  const ConstantNames& constant_names) {
  std::map<std::string, dialect::FunctionSignature, std::less<>> signatures;
  for (const Function& function : functions) signatures[function.name] = signature_of(function);
  std::map<std::string, dialect::Type, std::less<>> constant_types;
  for (const Constant& constant : constants) constant_types[constant.name] = *dialect::Type::from_name(constant.type);

  const auto collect = [&](const Function& function, const std::vector<std::string>& names, std::vector<std::string>& calls,
                           std::vector<std::string>& referenced_constants) {
    for (const std::string& name : names) {
      if (index.count(name) && name != function.name && !contains(calls, name)) calls.push_back(name);
      if (constant_names.count(name) && !contains(referenced_constants, name)) referenced_constants.push_back(name);
    }
  };
  for (Function& function : functions) {
    refuse_matrices(function);
    const dialect::SourcePlace place{function.source_file, function.body_line, function.name};
    auto tree = std::make_shared<dialect::Body>(dialect::parse_body(function.body, place));
    dialect::check_body(*tree, signatures.at(function.name), {&signatures, &constant_types, nullptr}, place);
    for (const std::string& name : dialect::referenced_names(*tree, std::nullopt)) {
      if (dialect::is_derivative_intrinsic(name)) function.fragment_only = true;
      if (name == "guarded") function.has_guards = true;
    }
    collect(function, dialect::referenced_names(*tree, true), function.calls, function.constants);
    collect(function, dialect::referenced_names(*tree, false), function.paper_calls, function.paper_constants);
    function.tree = std::move(tree);
  }
}

// Fragment-only propagates from callees to callers (a fixed point over the call graph); then a
// function's role must say whether it takes derivatives (helpers may either way).
void propagate_fragment_only(std::vector<Function>& functions, const FunctionIndex& index) {
  for (bool changed = true; changed;) {
    changed = false;
    for (Function& function : functions) {
      if (function.fragment_only) continue;
      const auto fragment_callee = [&](const std::string& callee) { return functions[index.at(callee)].fragment_only; };
      if (std::any_of(function.calls.begin(), function.calls.end(), fragment_callee) ||
          std::any_of(function.paper_calls.begin(), function.paper_calls.end(), fragment_callee)) {
        function.fragment_only = true;
        changed = true;
      }
    }
  }
  for (const Function& function : functions) {
    const bool must_be_fragment = function.role == FunctionRole::fragment;
    if (must_be_fragment != function.fragment_only && function.role != FunctionRole::helper) {
      fail(function.source_file, function.line,
           must_be_fragment ? fmt::format("{} has role fragment but takes no derivatives; use role core or evaluate", function.name)
                            : fmt::format("{} takes screen-space derivatives; its role must be fragment", function.name));
    }
  }
}

// Each variant is defined once and lists only known functions.
void check_variants(const std::vector<Variant>& variants, const FunctionIndex& index) {
  std::set<std::string> variant_ids;
  for (const Variant& variant : variants) {
    if (!variant_ids.insert(variant.id).second)
      fail(variant.source_file, variant.line, fmt::format("variant '{}' is defined twice", variant.id));
    for (const std::string& name : variant.functions) {
      if (!index.count(name)) {
        fail(variant.source_file, variant.line, fmt::format("variant {} lists unknown function '{}'", variant.id, name));
      }
    }
  }
}

}  // namespace

void Catalogue::link() {
  const ConstantNames constant_names = index_names(functions_, constants_, function_index_);
  parse_bodies(functions_, constants_, function_index_, constant_names);
  propagate_fragment_only(functions_, function_index_);
  check_variants(variants_, function_index_);
}

const Variant* Catalogue::find_variant(std::string_view id) const {
  for (const Variant& variant : variants_) {
    if (variant.id == id) return &variant;
  }
  return nullptr;
}

const Variant& Catalogue::variant(std::string_view id) const {
  const Variant* found = find_variant(id);
  if (!found) throw Error(fmt::format("unknown variant '{}'; run `saagen list` to see the ids", id));
  return *found;
}

const Function* Catalogue::find_function(std::string_view name) const {
  const auto found = function_index_.find(name);
  return found == function_index_.end() ? nullptr : &functions_[found->second];
}

const Constant* Catalogue::find_constant(std::string_view name) const {
  for (const Constant& constant : constants_) {
    if (constant.name == name) return &constant;
  }
  return nullptr;
}

const Constant* Catalogue::find_option(std::string_view option) const {
  for (const Constant& constant : constants_) {
    if (!constant.option.empty() && constant.option == option) return &constant;
  }
  return nullptr;
}

std::vector<const Function*> Catalogue::closure(const std::vector<std::string>& roots, bool guarded) const {
  std::vector<const Function*> ordered;
  std::set<const Function*> visited;
  std::function<void(const Function&)> visit = [&](const Function& function) {
    if (!visited.insert(&function).second) return;
    std::vector<const Function*> callees;
    for (const std::string& callee : guarded ? function.calls : function.paper_calls) callees.push_back(find_function(callee));
    std::sort(callees.begin(), callees.end());  // template order: functions_ is contiguous
    for (const Function* callee : callees) visit(*callee);
    ordered.push_back(&function);
  };
  std::vector<const Function*> root_functions;
  for (const std::string& root : roots) {
    const Function* function = find_function(root);
    if (!function) throw Error(fmt::format("unknown function '{}'", root));
    root_functions.push_back(function);
  }
  std::sort(root_functions.begin(), root_functions.end());
  for (const Function* function : root_functions) visit(*function);
  return ordered;
}

std::vector<const Constant*> Catalogue::constants_used(const std::vector<const Function*>& functions, bool guarded) const {
  std::vector<const Constant*> used;
  for (const Constant& constant : constants_) {
    const bool referenced = std::any_of(functions.begin(), functions.end(), [&](const Function* function) {
      return contains(guarded ? function->constants : function->paper_constants, constant.name);
    });
    if (referenced) used.push_back(&constant);
  }
  return used;
}

std::vector<std::string> resources_read(const Catalogue& catalogue, const std::vector<std::string>& roots) {
  std::set<std::string> names;
  for (const Function* function : catalogue.closure(roots)) {
    const auto tokens = dialect::tokenize(function->body);
    for (std::size_t index = 0; index < tokens.size(); ++index) {
      if (tokens[index].kind != dialect::TokenKind::identifier || dialect::is_member_access(tokens, index)) continue;
      for (const dialect::IntrinsicSignature& intrinsic : dialect::intrinsics()) {
        if (intrinsic.name == tokens[index].text && !intrinsic.resource.empty()) names.insert(intrinsic.resource);
      }
    }
  }
  return {names.begin(), names.end()};
}

bool is_screen_space_filter(const Catalogue& catalogue, const Variant& variant) {
  const auto has_role = [&](FunctionRole role) {
    return std::any_of(variant.functions.begin(), variant.functions.end(),
                       [&](const std::string& name) { return catalogue.find_function(name)->role == role; });
  };
  return has_role(FunctionRole::core) && has_role(FunctionRole::fragment);
}

dialect::FunctionSignature signature_of(const Function& function) {
  dialect::FunctionSignature signature;
  signature.result = *dialect::Type::from_name(function.return_type);
  for (const Parameter& parameter : function.parameters)
    signature.parameters.emplace_back(*dialect::Type::from_name(parameter.type), parameter.name);
  return signature;
}

bool supports_precision(const Variant& variant, Precision precision) {
  return variant.precisions.empty() ||
         std::find(variant.precisions.begin(), variant.precisions.end(), precision) != variant.precisions.end();
}

}  // namespace saagen
