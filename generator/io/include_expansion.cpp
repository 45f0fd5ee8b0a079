#include "saagen/io/include_expansion.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string_view>

namespace saagen {
namespace {

constexpr std::string_view deferred_error_token = "saagen_unresolved_include_";

// Three-valued: what the expansion knows of a condition (or of a line being compiled).
enum class Truth { no, yes, unknown };

Truth both(Truth a, Truth b) {
  if (a == Truth::no || b == Truth::no) return Truth::no;
  return a == Truth::yes && b == Truth::yes ? Truth::yes : Truth::unknown;
}

Truth negated(Truth a) { return a == Truth::unknown ? a : a == Truth::yes ? Truth::no : Truth::yes; }

bool is_identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\f\v");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\f\v");
  return text.substr(first, last - first + 1);
}

// The identifier at the start of `text` (after white space), empty if none; `rest` what follows.
std::string_view leading_identifier(std::string_view text, std::string_view* rest = nullptr) {
  text = trimmed(text);
  std::size_t end = 0;
  if (!text.empty() && is_identifier_start(text[0])) {
    while (end < text.size() && is_identifier_char(text[end])) ++end;
  }
  if (rest) *rest = text.substr(end);
  return text.substr(0, end);
}

// ---------------------------------------------------------------------------------------------
// Lines: comments removed (each replaced by a space, as translation phase 3 does), directives
// recognised.

enum class Directive { none, include, if_, ifdef, ifndef, elif, else_, endif, define, undef, pragma_once, other };

struct Line {
  std::string_view raw;  // as in the file, without its newline
  Directive directive = Directive::none;
  std::string rest;  // a directive's text after its name, comments removed
  bool significant = false;
};

// `line` with comments replaced by a space; `in_block` carries an open /* */ across lines.
// Quoted text ("...", an include's name) is kept as it is.
std::string without_comments(std::string_view line, bool& in_block) {
  std::string out;
  for (std::size_t at = 0; at < line.size();) {
    if (in_block) {
      const auto end = line.find("*/", at);
      if (end == std::string_view::npos) break;
      in_block = false;
      out += ' ';
      at = end + 2;
    } else if (line.compare(at, 2, "//") == 0) {
      out += ' ';
      break;
    } else if (line.compare(at, 2, "/*") == 0) {
      in_block = true;
      at += 2;
    } else if (line[at] == '"') {
      auto end = line.find('"', at + 1);
      end = end == std::string_view::npos ? line.size() : end + 1;
      out.append(line.substr(at, end - at));
      at = end;
    } else {
      out += line[at++];
    }
  }
  if (in_block) out += ' ';
  return out;
}

Directive directive_named(std::string_view name, std::string_view rest) {
  static const std::map<std::string_view, Directive> names = {
      {"include", Directive::include}, {"if", Directive::if_},        {"ifdef", Directive::ifdef},
      {"ifndef", Directive::ifndef},   {"elif", Directive::elif},     {"else", Directive::else_},
      {"endif", Directive::endif},     {"define", Directive::define}, {"undef", Directive::undef},
  };
  if (name == "pragma" && trimmed(rest) == "once") return Directive::pragma_once;
  const auto found = names.find(name);
  return found == names.end() ? Directive::other : found->second;
}

Line parse_line(std::string_view raw, bool& in_block) {
  Line line;
  line.raw = raw;
  const std::string text = without_comments(raw, in_block);
  const std::string_view content = trimmed(text);
  line.significant = !content.empty();
  if (content.empty() || content[0] != '#') return line;
  std::string_view rest;
  const std::string_view name = leading_identifier(content.substr(1), &rest);
  line.directive = name.empty() ? Directive::other : directive_named(name, rest);
  line.rest = std::string(trimmed(rest));
  return line;
}

// A file read once and split into lines; `guard` is X when every line that is not blank or a
// comment lies inside one `#ifndef X` (or `#if !defined(X)`) and its `#endif`, with no #else.
struct ParsedFile {
  std::shared_ptr<const IncludeFile> file;
  std::vector<Line> lines;
  std::string guard;
};

std::string guard_macro(const Line& line) {
  if (line.directive == Directive::ifndef) {
    std::string_view rest;
    const std::string_view name = leading_identifier(line.rest, &rest);
    return trimmed(rest).empty() ? std::string(name) : std::string();
  }
  if (line.directive != Directive::if_) return {};
  std::string_view text = trimmed(line.rest);
  if (text.empty() || text[0] != '!') return {};
  std::string_view rest;
  if (leading_identifier(text.substr(1), &rest) != "defined") return {};
  rest = trimmed(rest);
  const bool parenthesised = !rest.empty() && rest[0] == '(';
  const std::string_view name = leading_identifier(parenthesised ? rest.substr(1) : rest, &rest);
  rest = trimmed(rest);
  if (parenthesised) {
    if (rest.empty() || rest[0] != ')') return {};
    rest = trimmed(rest.substr(1));
  }
  return rest.empty() ? std::string(name) : std::string();
}

std::string find_guard(const std::vector<Line>& lines) {
  std::size_t first = 0;
  while (first < lines.size() && !lines[first].significant) ++first;
  if (first == lines.size()) return {};
  std::string guard = guard_macro(lines[first]);
  if (guard.empty()) return {};
  int depth = 0;
  for (std::size_t index = first; index < lines.size(); ++index) {
    const Directive directive = lines[index].directive;
    if (directive == Directive::if_ || directive == Directive::ifdef || directive == Directive::ifndef) ++depth;
    if ((directive == Directive::elif || directive == Directive::else_) && depth == 1) return {};
    if (directive == Directive::endif && --depth == 0) {
      for (std::size_t after = index + 1; after < lines.size(); ++after) {
        if (lines[after].significant) return {};
      }
      return guard;
    }
    if (depth == 0 && lines[index].significant) return {};
  }
  return {};
}

std::unique_ptr<ParsedFile> parse_file(std::shared_ptr<const IncludeFile> file) {
  auto parsed = std::make_unique<ParsedFile>();
  parsed->file = std::move(file);
  const std::string_view text = parsed->file->text;
  bool in_block = false;
  for (std::size_t at = 0; at < text.size();) {
    auto end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    parsed->lines.push_back(parse_line(text.substr(at, end - at), in_block));
    at = end + 1;
  }
  parsed->guard = find_guard(parsed->lines);
  return parsed;
}

// ---------------------------------------------------------------------------------------------
// Macros and #if expressions (C11 6.10.1: integer constant expressions, `defined`, identifiers
// that are no macro evaluate to 0), decided only where every macro involved is known.

struct Macro {
  enum class Kind { object, function, unknown } kind = Kind::unknown;
  std::string body;
};

// Names glslang predefines (GL_* and the extension names, VULKAN, __VERSION__, __LINE__,
// __FILE__; the HLSL front end's __SHADER_* and __HLSL_*): what they hold is glslang's to say.
bool reserved(std::string_view name) {
  return name.rfind("GL_", 0) == 0 || name == "VULKAN" || name == "__VERSION__" || name == "__LINE__" || name == "__FILE__" ||
         name.rfind("__SHADER", 0) == 0 || name.rfind("__HLSL", 0) == 0;
}

struct Value {
  bool known = false;
  std::int64_t number = 0;
};

Value known(std::int64_t number) { return {true, number}; }

struct Token {
  enum class Kind { number, identifier, punctuator, unknown } kind;
  std::string text;
  std::int64_t number = 0;
};

// Tokens of a #if expression; nullopt for text that is no integer expression (floats, strings).
std::optional<std::vector<Token>> tokenize(std::string_view text) {
  static const std::set<std::string_view> pairs = {"&&", "||", "==", "!=", "<=", ">=", "<<", ">>"};
  std::vector<Token> tokens;
  for (std::size_t at = 0; at < text.size();) {
    const char c = text[at];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++at;
    } else if (is_identifier_start(c)) {
      const std::size_t start = at;
      while (at < text.size() && is_identifier_char(text[at])) ++at;
      tokens.push_back({Token::Kind::identifier, std::string(text.substr(start, at - start))});
    } else if (std::isdigit(static_cast<unsigned char>(c))) {
      const std::size_t start = at;
      while (at < text.size() && is_identifier_char(text[at])) ++at;
      std::string digits(text.substr(start, at - start));
      while (!digits.empty() && (digits.back() == 'u' || digits.back() == 'U' || digits.back() == 'l' || digits.back() == 'L')) {
        digits.pop_back();
      }
      int base = 10;
      std::size_t first = 0;
      if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
        base = 16;
        first = 2;
      } else if (digits.size() > 1 && digits[0] == '0') {
        base = 8;
        first = 1;
      }
      std::uint64_t value = 0;
      for (std::size_t index = first; index < digits.size(); ++index) {
        const char digit = static_cast<char>(std::tolower(static_cast<unsigned char>(digits[index])));
        const int v = std::isdigit(static_cast<unsigned char>(digit)) ? digit - '0' : digit >= 'a' && digit <= 'f' ? digit - 'a' + 10 : 99;
        if (v >= base || value > (std::numeric_limits<std::uint64_t>::max() - static_cast<std::uint64_t>(v)) / base) return std::nullopt;
        value = value * base + static_cast<std::uint64_t>(v);
      }
      tokens.push_back({Token::Kind::number, {}, static_cast<std::int64_t>(value)});
    } else if (at + 1 < text.size() && pairs.count(text.substr(at, 2))) {
      tokens.push_back({Token::Kind::punctuator, std::string(text.substr(at, 2))});
      at += 2;
    } else if (std::string_view("!~-+*/%<>&^|()?:").find(c) != std::string_view::npos) {
      tokens.push_back({Token::Kind::punctuator, std::string(1, c)});
      ++at;
    } else {
      return std::nullopt;
    }
  }
  return tokens;
}

// Evaluates one #if expression against the macros known so far.
class Condition {
 public:
  // `budget`: the work left to all #if evaluations of one expansion (tokens visited, macro body
  // bytes read); once spent, every condition is glslang's to decide.
  Condition(const std::map<std::string, Macro, std::less<>>& macros, std::size_t& budget) : macros_(macros), budget_(budget) {}

  Truth evaluate(std::string_view text) {
    const auto tokens = tokenize(text);
    if (!tokens) return Truth::unknown;
    if (!substitute(*tokens, 0)) return Truth::unknown;
    at_ = 0;
    depth_ = 0;
    const auto value = conditional();
    if (!value || at_ != tokens_.size() || !value->known) return Truth::unknown;
    return value->number != 0 ? Truth::yes : Truth::no;
  }

  // What `#ifdef name` knows.
  static Truth defined(const std::map<std::string, Macro, std::less<>>& macros, std::string_view name) {
    const auto found = macros.find(name);
    if (found == macros.end()) return reserved(name) ? Truth::unknown : Truth::no;
    return found->second.kind == Macro::Kind::unknown ? Truth::unknown : Truth::yes;
  }

 private:
  static constexpr std::size_t token_budget = 4096;  // macro expansion of one expression
  static constexpr int nesting_limit = 200;

  // Replaces `defined X` by 0/1 and macros by their bodies (an unknown one by an unknown token).
  bool substitute(const std::vector<Token>& tokens, int depth) {
    if (depth > 32) return false;
    for (std::size_t index = 0; index < tokens.size(); ++index) {
      if (tokens_.size() > token_budget || budget_ == 0) return false;
      --budget_;
      const Token& token = tokens[index];
      if (token.kind != Token::Kind::identifier) {
        tokens_.push_back(token);
        continue;
      }
      if (token.text == "defined") {
        std::size_t next = index + 1;
        const bool parenthesised = next < tokens.size() && tokens[next].text == "(";
        if (parenthesised) ++next;
        if (next >= tokens.size() || tokens[next].kind != Token::Kind::identifier) return false;
        if (parenthesised && (next + 1 >= tokens.size() || tokens[next + 1].text != ")")) return false;
        const Truth truth = defined(macros_, tokens[next].text);
        tokens_.push_back(truth == Truth::unknown ? Token{Token::Kind::unknown, {}}
                                                  : Token{Token::Kind::number, {}, truth == Truth::yes ? 1 : 0});
        index = parenthesised ? next + 1 : next;
        continue;
      }
      const auto found = macros_.find(token.text);
      if (found == macros_.end()) {
        tokens_.push_back(reserved(token.text) ? Token{Token::Kind::unknown, {}} : Token{Token::Kind::number, {}, 0});
        continue;
      }
      if (found->second.kind != Macro::Kind::object || expanding_.count(token.text)) {
        tokens_.push_back({Token::Kind::unknown, {}});
        continue;
      }
      if (found->second.body.size() >= budget_) return false;
      budget_ -= found->second.body.size();
      const auto body = tokenize(found->second.body);
      if (!body) return false;
      expanding_.insert(token.text);
      const bool ok = substitute(*body, depth + 1);
      expanding_.erase(token.text);
      if (!ok) return false;
    }
    return true;
  }

  const Token* peek() const { return at_ < tokens_.size() ? &tokens_[at_] : nullptr; }
  bool accept(std::string_view punctuator) {
    if (peek() && peek()->kind == Token::Kind::punctuator && peek()->text == punctuator) {
      ++at_;
      return true;
    }
    return false;
  }

  std::optional<Value> conditional() {
    if (++depth_ > nesting_limit) return std::nullopt;
    auto condition = binary(1);
    if (condition && accept("?")) {
      const auto then = conditional();
      if (!then || !accept(":")) return std::nullopt;
      const auto otherwise = conditional();
      if (!otherwise) return std::nullopt;
      if (!condition->known)
        condition = then->known && otherwise->known && then->number == otherwise->number ? then : Value{};
      else
        condition = condition->number != 0 ? then : otherwise;
    }
    --depth_;
    return condition;
  }

  static int precedence(std::string_view op) {
    static const std::map<std::string_view, int> table = {{"||", 1}, {"&&", 2}, {"|", 3}, {"^", 4},  {"&", 5},  {"==", 6},
                                                          {"!=", 6}, {"<", 7},  {">", 7}, {"<=", 7}, {">=", 7}, {"<<", 8},
                                                          {">>", 8}, {"+", 9},  {"-", 9}, {"*", 10}, {"/", 10}, {"%", 10}};
    const auto found = table.find(op);
    return found == table.end() ? 0 : found->second;
  }

  std::optional<Value> binary(int minimum) {
    auto left = unary();
    while (left) {
      const Token* token = peek();
      if (!token || token->kind != Token::Kind::punctuator) break;
      const int level = precedence(token->text);
      if (level < minimum || level == 0) break;
      const std::string op = token->text;
      ++at_;
      const auto right = binary(level + 1);
      if (!right) return std::nullopt;
      left = apply(op, *left, *right);
    }
    return left;
  }

  std::optional<Value> unary() {
    if (++depth_ > nesting_limit) return std::nullopt;
    std::optional<Value> result;
    const Token* token = peek();
    if (!token) return std::nullopt;
    if (token->kind == Token::Kind::number) {
      ++at_;
      result = known(token->number);
    } else if (token->kind == Token::Kind::unknown) {
      ++at_;
      result = Value{};
    } else if (accept("(")) {
      result = conditional();
      if (!accept(")")) return std::nullopt;
    } else if (token->kind == Token::Kind::punctuator && std::string_view("!~-+").find(token->text) != std::string_view::npos &&
               token->text.size() == 1) {
      const char op = token->text[0];
      ++at_;
      const auto operand = unary();
      if (!operand) return std::nullopt;
      const auto bits = static_cast<std::uint64_t>(operand->number);
      result = !operand->known ? Value{}
               : op == '!'     ? known(operand->number == 0)
               : op == '~'     ? known(static_cast<std::int64_t>(~bits))
               : op == '-'     ? known(static_cast<std::int64_t>(0 - bits))
                               : *operand;
    } else {
      return std::nullopt;
    }
    --depth_;
    return result;
  }

  static Value apply(const std::string& op, Value a, Value b) {
    if (op == "&&") {
      if ((a.known && a.number == 0) || (b.known && b.number == 0)) return known(0);
      return a.known && b.known ? known(1) : Value{};
    }
    if (op == "||") {
      if ((a.known && a.number != 0) || (b.known && b.number != 0)) return known(1);
      return a.known && b.known ? known(0) : Value{};
    }
    if (!a.known || !b.known) return {};
    const auto x = static_cast<std::uint64_t>(a.number), y = static_cast<std::uint64_t>(b.number);
    if (op == "+") return known(static_cast<std::int64_t>(x + y));
    if (op == "-") return known(static_cast<std::int64_t>(x - y));
    if (op == "*") return known(static_cast<std::int64_t>(x * y));
    if (op == "/" || op == "%") {
      if (b.number == 0 || (a.number == std::numeric_limits<std::int64_t>::min() && b.number == -1)) return {};
      return known(op == "/" ? a.number / b.number : a.number % b.number);
    }
    if (op == "<<" || op == ">>") {
      if (b.number < 0 || b.number >= 64) return {};
      return known(op == "<<" ? static_cast<std::int64_t>(x << b.number) : a.number >> b.number);
    }
    if (op == "<") return known(a.number < b.number);
    if (op == ">") return known(a.number > b.number);
    if (op == "<=") return known(a.number <= b.number);
    if (op == ">=") return known(a.number >= b.number);
    if (op == "==") return known(a.number == b.number);
    if (op == "!=") return known(a.number != b.number);
    if (op == "&") return known(a.number & b.number);
    if (op == "^") return known(a.number ^ b.number);
    return known(a.number | b.number);
  }

  const std::map<std::string, Macro, std::less<>>& macros_;
  std::vector<Token> tokens_;
  std::set<std::string, std::less<>> expanding_;
  std::size_t& budget_;
  std::size_t at_ = 0;
  int depth_ = 0;
};

// ---------------------------------------------------------------------------------------------
// The expansion.

// What an include line names: a file ("..."), a generated snippet (<saagen/...>), or neither.
struct IncludeName {
  enum class Kind { file, generated, unsupported, unterminated, missing } kind;
  std::string name;
};

IncludeName include_name(std::string_view rest) {
  rest = trimmed(rest);
  if (rest.empty()) return {IncludeName::Kind::missing, {}};
  const char close = rest[0] == '"' ? '"' : rest[0] == '<' ? '>' : '\0';
  if (close == '\0') return {IncludeName::Kind::unsupported, {}};
  const auto end = rest.find(close, 1);
  if (end == std::string_view::npos) return {IncludeName::Kind::unterminated, {}};
  const std::string name(rest.substr(1, end - 1));
  if (close == '"') return {IncludeName::Kind::file, name};
  return {name.rfind("saagen/", 0) == 0 ? IncludeName::Kind::generated : IncludeName::Kind::unsupported, name};
}

class Expander {
 public:
  Expander(const IncludeSources& sources, const IncludeLimits& limits) : sources_(sources), limits_(limits) {}

  void expand(const ParsedFile& file, int depth) {
    std::string chunk;
    for (std::size_t index = 0; index < file.lines.size(); ++index) {
      const Line& line = file.lines[index];
      const int number = static_cast<int>(index) + 1;
      if (line.directive == Directive::include) {
        if (include(file, line, number, depth, chunk)) chunk = fmt::format("#line {}\n", number + 1);
        continue;
      }
      directive(file, line);
      if (line.directive == Directive::pragma_once && live() == Truth::yes) {
        chunk += "\n";  // done here; glslang would only warn that it does not implement it
        continue;
      }
      append(chunk, line.raw, file, number);
      append(chunk, "\n", file, number);
    }
    flush(file.file->name, chunk);
  }

  std::vector<ExpandedPiece>& pieces() { return pieces_; }
  std::vector<std::string>& deferred_errors() { return deferred_errors_; }

 private:
  struct Conditional {
    Truth parent;
    Truth branch;
    Truth taken;  // whether an earlier branch (or this one) is compiled
  };

  Truth live() const { return stack_.empty() ? Truth::yes : stack_.back().branch; }

  std::string where(const ParsedFile& file, int number) const { return fmt::format("{}:{}", file.file->name, number); }

  void append(std::string& chunk, std::string_view text, const ParsedFile& file, int number) {
    bytes_ += text.size();
    if (bytes_ > limits_.total_bytes) {
      throw Error(fmt::format(
          "{}: the #include expansion exceeds {} MiB in all (an include bomb?); guard each header with #ifndef/#define/#endif or "
          "#pragma once so that it is expanded once",
          where(file, number), limits_.total_bytes >> 20));
    }
    chunk.append(text);
  }

  void flush(const std::string& name, std::string& chunk) {
    if (!chunk.empty()) pieces_.push_back({name, std::move(chunk)});
    chunk.clear();
  }

  void directive(const ParsedFile& file, const Line& line) {
    switch (line.directive) {
      case Directive::if_:
      case Directive::ifdef:
      case Directive::ifndef: {
        const Truth parent = live();
        if (parent == Truth::no) {
          stack_.push_back({Truth::no, Truth::no, Truth::yes});
          break;
        }
        const Truth value = condition(line);
        stack_.push_back({parent, both(parent, value), value});
        break;
      }
      case Directive::elif:
      case Directive::else_: {
        if (stack_.empty()) break;  // glslang reports it
        Conditional& top = stack_.back();
        if (top.parent == Truth::no || top.taken == Truth::yes) {
          top.branch = Truth::no;
          break;
        }
        const Truth value = line.directive == Directive::else_ ? Truth::yes : condition(line);
        if (top.taken == Truth::no) {
          top.branch = both(top.parent, value);
          top.taken = value;
        } else {
          top.branch = value == Truth::no ? Truth::no : both(top.parent, Truth::unknown);
          top.taken = value == Truth::yes ? Truth::yes : Truth::unknown;
        }
        break;
      }
      case Directive::endif:
        if (!stack_.empty()) stack_.pop_back();
        break;
      case Directive::define:
      case Directive::undef:
        define(line);
        break;
      case Directive::pragma_once:
        if (live() == Truth::yes) once_.insert(file.file->identity);
        break;
      default:
        break;
    }
  }

  Truth condition(const Line& line) {
    if (line.directive == Directive::if_ || line.directive == Directive::elif)
      return Condition(macros_, evaluation_budget_).evaluate(line.rest);
    std::string_view rest;
    const std::string_view name = leading_identifier(line.rest, &rest);
    const Truth defined = name.empty() ? Truth::unknown : Condition::defined(macros_, name);
    return line.directive == Directive::ifdef ? defined : negated(defined);
  }

  void define(const Line& line) {
    const Truth state = live();
    if (state == Truth::no) return;
    std::string_view rest;
    const std::string name(leading_identifier(line.rest, &rest));
    if (name.empty()) return;
    if (state == Truth::unknown) {
      macros_[name] = Macro{};
    } else if (line.directive == Directive::undef) {
      macros_.erase(name);
    } else {
      // Function-like when '(' follows the name at once (C11 6.10.3p3).
      const auto after = line.rest.find(name) + name.size();
      const bool function = after < line.rest.size() && line.rest[after] == '(';
      macros_[name] = function ? Macro{Macro::Kind::function, {}} : Macro{Macro::Kind::object, std::string(trimmed(rest))};
    }
  }

  // Handles one #include line; true when pieces were added (the including file then goes on
  // after a #line directive).
  bool include(const ParsedFile& file, const Line& line, int number, int depth, std::string& chunk) {
    const Truth state = live();
    if (state == Truth::no) {
      append(chunk, "\n", file, number);  // skipped, as the preprocessor skips it
      return false;
    }
    const IncludeName target = include_name(line.rest);
    std::string problem;
    if (target.kind == IncludeName::Kind::missing) problem = "#include names no file";
    if (target.kind == IncludeName::Kind::unterminated) problem = "unterminated #include";
    if (target.kind == IncludeName::Kind::unsupported) {
      problem = "only #include \"FILE\" (searched next to the file, then in -I directories) and #include <saagen/...> are supported";
    }
    const ParsedFile* included = nullptr;
    if (problem.empty() && target.kind == IncludeName::Kind::generated) {
      try {
        included = &generated(target.name);
      } catch (const Error& error) {
        problem = error.what();
      }
    } else if (problem.empty()) {
      auto found = sources_.find(target.name, *file.file);
      if (found)
        included = &parsed(std::move(found));
      else
        problem = fmt::format("#include \"{}\" not found next to the file or in the -I directories", target.name);
    }
    if (!problem.empty()) {
      if (state == Truth::yes) throw Error(fmt::format("{}: {}", where(file, number), problem));
      // Compiled or not is glslang's to decide: an error there only if it is.
      deferred_errors_.push_back(fmt::format("{}: {}", where(file, number), problem));
      append(chunk, fmt::format("#error {}{}\n", deferred_error_token, deferred_errors_.size() - 1), file, number);
      return false;
    }
    if (++includes_ > limits_.includes) {
      throw Error(fmt::format(
          "{}: more than {} #include expansions in all (an include bomb?); guard each header with #ifndef/#define/#endif or #pragma "
          "once so that it is expanded once",
          where(file, number), limits_.includes));
    }
    if (once_.count(included->file->identity) || (!included->guard.empty() && Condition::defined(macros_, included->guard) == Truth::yes)) {
      append(chunk, "\n", file, number);  // wholly skipped by its guard: nothing to compile
      return false;
    }
    if (depth + 1 > limits_.depth) {
      throw Error(fmt::format("{}: #include nested deeper than {} (a cycle? guard the header with #ifndef/#define/#endif or #pragma once)",
                              where(file, number), limits_.depth));
    }
    flush(file.file->name, chunk);
    expand(*included, depth + 1);
    return true;
  }

  // A file split into lines once (by identity; the same object, or the same text, as before).
  const ParsedFile& parsed(std::shared_ptr<const IncludeFile> file) {
    auto found = cache_.find(file->identity);
    if (found != cache_.end() && (found->second->file == file || found->second->file->text == file->text)) return *found->second;
    const std::string identity = file->identity;
    auto& slot = cache_[identity];
    if (slot) retired_.push_back(std::move(slot));  // still referenced by an expansion in progress
    slot = parse_file(std::move(file));
    return *slot;
  }

  // A generated snippet, asked for once per name and then read like a file (its guard applies).
  const ParsedFile& generated(const std::string& name) {
    auto& slot = generated_[name];
    if (!slot) slot = parse_file(std::make_shared<const IncludeFile>(IncludeFile{name, "<" + name + ">", sources_.generated(name)}));
    return *slot;
  }

  const IncludeSources& sources_;
  const IncludeLimits& limits_;
  std::vector<ExpandedPiece> pieces_;
  std::vector<std::string> deferred_errors_;
  std::vector<Conditional> stack_;
  std::map<std::string, Macro, std::less<>> macros_;
  std::set<std::string> once_;
  std::map<std::string, std::unique_ptr<ParsedFile>> cache_;
  std::map<std::string, std::unique_ptr<ParsedFile>> generated_;
  std::vector<std::unique_ptr<ParsedFile>> retired_;
  std::size_t bytes_ = 0;
  std::size_t includes_ = 0;
  std::size_t evaluation_budget_ = std::size_t{1} << 24;
};

}  // namespace

IncludeExpansion expand_includes(const IncludeFile& root, const IncludeSources& sources, const IncludeLimits& limits) {
  Expander expander(sources, limits);
  const auto parsed = parse_file(std::make_shared<const IncludeFile>(root));
  expander.expand(*parsed, 0);
  return {std::move(expander.pieces()), std::move(expander.deferred_errors())};
}

std::optional<std::string> deferred_include_error(const IncludeExpansion& expansion, std::string_view compiler_message) {
  const auto at = compiler_message.find(deferred_error_token);
  if (at == std::string_view::npos) return std::nullopt;
  std::size_t index = 0, digits = 0;
  for (std::size_t next = at + deferred_error_token.size();
       next < compiler_message.size() && std::isdigit(static_cast<unsigned char>(compiler_message[next])) && digits < 9; ++next, ++digits) {
    index = index * 10 + static_cast<std::size_t>(compiler_message[next] - '0');
  }
  if (digits == 0 || index >= expansion.deferred_errors.size()) return std::nullopt;
  return expansion.deferred_errors[index];
}

}  // namespace saagen
