// The portable template dialect: a C-like token stream shared by every target. See
// templates/README.md for the language itself.
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

// Resolves every `guarded(safe, paper)` in `code` to `(safe)` when `guarded` is true, else to
// `(paper)`. Guards protect the paper's formula where it breaks (division by |h_z|, a zero
// vector, an overflowing product); `saagen emit --unguarded` emits the paper form. Throws
// saagen::Error when a guarded(...) does not have exactly two arguments.
std::string resolve_guards(std::string_view code, bool guarded);

// The dialect's scalar and vector types. There are deliberately no matrix types.
const std::vector<std::string>& type_names();
// Intrinsics that take screen-space derivatives: a function using one is fragment-only.
const std::vector<std::string>& derivative_intrinsics();
// Names that would import a target's matrix convention; templates may not use them.
const std::vector<std::string>& forbidden_names();

}  // namespace saagen::dialect
