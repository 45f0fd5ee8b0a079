#include "saagen/front/dialect.hpp"

#include <cctype>
#include <string>

namespace saagen::dialect {
namespace {

bool is_identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::size_t scan_number(std::string_view code, std::size_t begin) {
  std::size_t end = begin;
  while (end < code.size()) {
    const char c = code[end];
    const bool exponent_sign = (c == '+' || c == '-') && end > begin && (code[end - 1] == 'e' || code[end - 1] == 'E');
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || exponent_sign)) break;
    ++end;
  }
  return end;
}

}  // namespace

std::vector<Token> tokenize(std::string_view code) {
  std::vector<Token> tokens;
  std::size_t index = 0;
  while (index < code.size()) {
    const char c = code[index];
    std::size_t end = index + 1;
    TokenKind kind = TokenKind::punctuation;
    if (is_space(c)) {
      kind = TokenKind::whitespace;
      while (end < code.size() && is_space(code[end])) ++end;
    } else if (c == '/' && index + 1 < code.size() && code[index + 1] == '/') {
      kind = TokenKind::comment;
      end = code.find('\n', index);
      if (end == std::string_view::npos) end = code.size();
    } else if (is_identifier_start(c)) {
      kind = TokenKind::identifier;
      while (end < code.size() && is_identifier_char(code[end])) ++end;
    } else if (is_digit(c) || (c == '.' && index + 1 < code.size() && is_digit(code[index + 1]))) {
      kind = TokenKind::number;
      end = scan_number(code, index);
    } else if ((c == '|' || c == '&' || c == '=' || c == '<' || c == '>' || c == '!') && index + 1 < code.size() &&
               (code[index + 1] == c || code[index + 1] == '=')) {
      end = index + 2;  // ||, &&, ==, <=, >=, !=
    }
    tokens.push_back({kind, code.substr(index, end - index)});
    index = end;
  }
  return tokens;
}

std::size_t next_significant(const std::vector<Token>& tokens, std::size_t index) {
  for (std::size_t next = index + 1; next < tokens.size(); ++next) {
    if (tokens[next].kind != TokenKind::whitespace && tokens[next].kind != TokenKind::comment) return next;
  }
  return tokens.size();
}

bool is_member_access(const std::vector<Token>& tokens, std::size_t index) {
  for (std::size_t previous = index; previous-- > 0;) {
    if (tokens[previous].kind == TokenKind::whitespace || tokens[previous].kind == TokenKind::comment) continue;
    return tokens[previous].text == ".";
  }
  return false;
}

const std::vector<std::string>& type_names() {
  static const std::vector<std::string> names = {"real", "real2", "real3", "real4", "bool", "int"};
  return names;
}

const std::vector<std::string>& forbidden_names() {
  static const std::vector<std::string> names = {"mul",      "transpose", "determinant", "mat2",     "mat3",     "mat4",
                                                 "mat2x2",   "mat3x3",    "mat4x4",      "float2x2", "float3x3", "float4x4",
                                                 "float3x4", "float4x3",  "real2x2",     "real3x3",  "real4x4"};
  return names;
}

}  // namespace saagen::dialect
