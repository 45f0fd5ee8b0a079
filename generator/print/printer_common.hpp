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

// The walk both printers share, over their own `print(const Expr&)` and grouping rule
// `parenthesise(parent, position, child)` (needs_parentheses, or WGSL's stricter one).
//
// Operand `position` of `parent`, after the layout `canonical` (or the template's line break),
// in parentheses where the rule needs them.
template <class Print, class Parenthesise>
std::string operand_text(const Expr& parent, std::size_t position, std::string_view canonical, Print print, Parenthesise parenthesise) {
  const Expr& child = *parent.operands[position];
  const std::string text = print(child);
  const std::string layout = position == 0 && parent.kind != ExprKind::unary ? std::string() : spacing(child.leading, canonical);
  return layout + (parenthesise(parent, position, child) ? "(" + text + ")" : text);
}

// An operand after a token: its own line break if it starts a line, else `canonical`.
template <class Print>
std::string spaced_text(const Expr& expr, std::string_view canonical, Print print) {
  return spacing(expr.leading, canonical) + print(expr);
}

// A call's arguments, comma-separated, each after its own line break or a space.
template <class Print>
std::string arguments_text(const Expr& expr, Print print) {
  std::string out;
  for (std::size_t index = 0; index < expr.operands.size(); ++index) {
    out += (index == 0 ? "" : ",") + spaced_text(*expr.operands[index], index == 0 ? "" : " ", print);
  }
  return out;
}

}  // namespace saagen::dialect::printing
