// What the printers of the typed syntax tree share (c_like_printer.cpp, wgsl_printer.cpp): C's
// operator precedence with the grouping that compilers and WGSL ask for, the template's layout,
// and the expansion of a syntax table's intrinsic patterns.
#pragma once

#include "saagen/front/syntax_tree.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace saagen::dialect::printing {

// C's binding strength: 1 assignment ... 12 multiplicative, 13 prefix, 14 postfix, 15 primary.
int precedence(const Expr& expr);
// Whether `child` must be parenthesised as operand `position` of `parent`.
bool needs_parentheses(const Expr& parent, std::size_t position, const Expr& child);
bool has_line_break(std::string_view layout);
// The template's layout where it breaks the line, else the canonical spacing.
std::string spacing(std::string_view layout, std::string_view canonical);

}  // namespace saagen::dialect::printing
