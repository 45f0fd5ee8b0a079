// The portable template dialect's tokens (templates/README.md). Function bodies are parsed from
// them into the typed syntax tree of saagen/front/syntax_tree.hpp; the derivative intrinsics and every
// other intrinsic signature are data (templates/intrinsics.sig).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace saagen::dialect {

enum class TokenKind { identifier, number, punctuation, whitespace, comment };

struct Token {
  TokenKind kind;
  std::string_view text;
};

// Splits code into tokens; concatenating the texts gives back the input exactly.
std::vector<Token> tokenize(std::string_view code);

// Index of the next token after `index` that is neither whitespace nor a comment, or
// tokens.size() when there is none.
std::size_t next_significant(const std::vector<Token>& tokens, std::size_t index);

// True when the identifier at `index` is a member access (`v.xy`), i.e. preceded by '.'.
bool is_member_access(const std::vector<Token>& tokens, std::size_t index);

// The dialect's scalar and vector types. There are deliberately no matrix types.
const std::vector<std::string>& type_names();
// Names that would import a target's matrix convention; templates may not use them.
const std::vector<std::string>& forbidden_names();

}  // namespace saagen::dialect
