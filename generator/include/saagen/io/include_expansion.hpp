// #include expansion for `saagen compile`, as a preprocessor sees it: an #include inside a
// comment or in a branch of #if/#ifdef/#ifndef/#elif/#else that is known to be skipped is not
// resolved; a header wholly inside `#ifndef X ... #endif` is skipped once X is defined, and one
// with `#pragma once` is read once, so a guarded include tree costs time and memory linear in
// its distinct text; a total budget refuses include bombs in one line. What the expansion
// cannot decide (a macro glslang predefines, a function-like macro) stays with glslang: such a
// branch is expanded, and an include there that is missing becomes an #error line that glslang
// reports only if the branch is compiled.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// A source file as the expansion reads it.
struct IncludeFile {
  std::string name;      // as messages and the compiler's source pieces name it
  std::string identity;  // equal for two names of one file (#pragma once compares it)
  std::string text;
};

struct IncludeSources {
  // The file `#include "requested"` in `from` names, null when there is none; throws
  // saagen::Error for one that exists and cannot be read. Returning the same object for the same
  // file spares comparing its text.
  std::function<std::shared_ptr<const IncludeFile>(const std::string& requested, const IncludeFile& from)> find;
  // The text of `#include <saagen/...>` (`name` without the brackets), asked for once per name;
  // throws saagen::Error.
  std::function<std::string(const std::string& name)> generated;
};

struct IncludeLimits {
  int depth = 32;                                   // nested includes
  std::size_t total_bytes = std::size_t{64} << 20;  // text of the whole expansion
  std::size_t includes = 65536;                     // includes expanded, all files together
};

// One source string for the compiler: a file's text up to an #include (or its end); after an
// include the including file's next piece starts with `#line N`.
struct ExpandedPiece {
  std::string name;
  std::string text;
};

struct IncludeExpansion {
  std::vector<ExpandedPiece> pieces;
  // The one-line errors of includes in branches only glslang can decide: the pieces hold
  // `#error saagen_unresolved_include_K` there, K indexing this list.
  std::vector<std::string> deferred_errors;
};

// Expands `root`. Throws saagen::Error in one line starting with FILE:LINE: for an include that
// is compiled and cannot be found, an include nested deeper than limits.depth, or an expansion
// beyond the budget.
IncludeExpansion expand_includes(const IncludeFile& root, const IncludeSources& sources, const IncludeLimits& limits = {});

// The deferred error a compiler message reports (its #error line fired), if any.
std::optional<std::string> deferred_include_error(const IncludeExpansion& expansion, std::string_view compiler_message);

}  // namespace saagen
