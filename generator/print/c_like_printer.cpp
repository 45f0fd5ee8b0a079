// The printer of the typed syntax tree for C-like targets (GLSL, HLSL, GLSL ES): statements and
// expressions keep the dialect's C syntax; the target's syntax table spells the types and the
// intrinsics (patterns with {0}, {1}, ...); template names get the emission's prefix. Line breaks
// and comments of the template are kept where they are; spacing inside a line is canonical.
#include "printer_common.hpp"

#include "saagen/error.hpp"
#include "saagen/front/syntax_tree.hpp"
#include "saagen/target/target.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace saagen::dialect {
namespace printing {

// C's binding strength: 1 assignment ... 12 multiplicative, 13 prefix, 14 postfix, 15 primary.
int precedence(const Expr& expr) {
  static const std::pair<std::string_view, int> binary[] = {{"||", 3},  {"&&", 4}, {"|", 5},  {"^", 6},  {"&", 7},  {"==", 8},
                                                            {"!=", 8},  {"<", 9},  {">", 9},  {"<=", 9}, {">=", 9}, {"<<", 10},
                                                            {">>", 10}, {"+", 11}, {"-", 11}, {"*", 12}, {"/", 12}, {"%", 12}};
  switch (expr.kind) {
    case ExprKind::assign:
      return 1;
    case ExprKind::ternary:
      return 2;
    case ExprKind::binary:
      for (const auto& [op, level] : binary) {
        if (op == expr.text) return level;
      }
      return 0;
    case ExprKind::unary:
      return 13;
    case ExprKind::member:
    case ExprKind::index:
    case ExprKind::postfix:
      return 14;
    default:
      return 15;
  }
}

// Whether `child` must be parenthesised as operand `position` of `parent` (the template's own
// parentheses are group nodes: they are printed as written and are never doubled).
bool needs_parentheses(const Expr& parent, std::size_t position, const Expr& child) {
  const int inner = precedence(child);
  switch (parent.kind) {
    case ExprKind::binary: {
      // Bitwise, equality, relational and shift operators mixed with each other, and arithmetic
      // inside bitwise or shift operators, are grouped although C would not need it (a < b == c;
      // n & 3 + 1): as compilers warn (-Wparentheses), and as WGSL requires.
      const int outer = precedence(parent);
      const bool bitwise_or_shift = (outer >= 5 && outer <= 7) || outer == 10;
      const bool mixed = child.kind == ExprKind::binary && child.text != parent.text &&
                         ((inner >= 5 && inner <= 10 && outer >= 5 && outer <= 10) || (bitwise_or_shift && inner >= 11));
      return mixed || (position == 0 ? inner < outer : inner <= outer);
    }
    case ExprKind::assign:
      return position == 0 ? inner < 14 : inner < 1;
    case ExprKind::ternary:
      return position == 0 ? inner <= 2 : inner < 2;
    case ExprKind::unary:
      return inner < 13 || (child.kind == ExprKind::unary && child.text == parent.text);
    case ExprKind::member:
    case ExprKind::index:
    case ExprKind::postfix:
      return position == 0 && inner < 14;
    default:
      return false;
  }
}

bool has_line_break(std::string_view layout) { return layout.find('\n') != std::string_view::npos; }

// The template's layout where it breaks the line, else the canonical spacing.
std::string spacing(std::string_view layout, std::string_view canonical) {
  return std::string(has_line_break(layout) ? layout : canonical);
}

}  // namespace printing

namespace {
using namespace printing;

class CLikePrinter {
 public:
  CLikePrinter(const TargetSyntax& target, const NameMap& names, bool guarded) : target_(target), names_(names), guarded_(guarded) {}

  std::string body(const Body& body) const {
    std::string out;
    for (const auto& stmt : body.statements) out += stmt->leading + statement(*stmt);
    return out + body.trailing;
  }

  std::string expression(const Expr& expr) const {
    switch (expr.kind) {
      case ExprKind::literal:
        return expr.text;
      case ExprKind::name:
        return name(expr.text);
      case ExprKind::group:
        return "(" + spaced(*expr.operands[0], "") + spacing(expr.separators[0], "") + ")";
      case ExprKind::unary:
        return expr.text + operand(expr, 0, "");
      case ExprKind::binary:
      case ExprKind::assign:
        return operand(expr, 0, "") + spacing(expr.separators[0], " ") + expr.text + operand(expr, 1, " ");
      case ExprKind::ternary:
        return operand(expr, 0, "") + spacing(expr.separators[0], " ") + "?" + operand(expr, 1, " ") + spacing(expr.separators[1], " ") +
               ":" + operand(expr, 2, " ");
      case ExprKind::call:
        return call(expr);
      case ExprKind::member:
        return operand(expr, 0, "") + "." + expr.text;
      case ExprKind::postfix:
        return operand(expr, 0, "") + expr.text;
      case ExprKind::index:
        return operand(expr, 0, "") + "[" + spaced(*expr.operands[1], "") + spacing(expr.separators[0], "") + "]";
      case ExprKind::guarded:
        return "(" + expression(*expr.operands[guarded_ ? 0 : 1]) + ")";
    }
    return {};
  }

 private:
  std::string name(const std::string& text) const {
    const auto found = names_.find(text);
    return found == names_.end() ? text : found->second;
  }

  auto printer() const {
    return [this](const Expr& expr) { return expression(expr); };
  }
  std::string operand(const Expr& parent, std::size_t position, std::string_view canonical) const {
    return operand_text(parent, position, canonical, printer(), needs_parentheses);
  }
  std::string spaced(const Expr& expr, std::string_view canonical) const { return spaced_text(expr, canonical, printer()); }

  std::string call(const Expr& expr) const {
    if (expr.call_kind == CallKind::intrinsic) {
      const auto pattern = target_.intrinsics.find(expr.text);
      if (pattern != target_.intrinsics.end()) {
        std::vector<std::string> arguments;
        for (const auto& operand : expr.operands) arguments.push_back(expression(*operand));
        return expand_pattern(pattern->second, arguments);
      }
    }
    std::string callee = expr.text;
    if (expr.call_kind == CallKind::constructor)
      callee = target_.types.at(expr.text);
    else if (expr.call_kind == CallKind::function)
      callee = name(expr.text);
    return callee + "(" + arguments_text(expr, printer()) + spacing(expr.separators[0], "") + ")";
  }

  // A statement without its leading layout.
  std::string statement(const Stmt& stmt) const {
    switch (stmt.kind) {
      case StmtKind::declaration:
        return target_.types.at(stmt.type_name) + " " + stmt.name + (stmt.value ? " =" + spaced(*stmt.value, " ") : "") + ";";
      case StmtKind::expression:
        return expression(*stmt.value) + ";";
      case StmtKind::return_value:
        return "return" + (stmt.value ? spaced(*stmt.value, " ") : "") + ";";
      case StmtKind::conditional: {
        std::string out = "if (" + spaced(*stmt.value, "") + ")" + nested(*stmt.body[0]);
        if (stmt.body.size() == 2) out += spacing(stmt.closing, " ") + "else" + nested(*stmt.body[1]);
        return out;
      }
      case StmtKind::block: {
        std::string out = "{";
        for (const auto& inner : stmt.body) out += inner->leading + statement(*inner);
        return out + stmt.closing + "}";
      }
      case StmtKind::loop_for:
        return "for (" + statement(*stmt.init) + (stmt.value ? spaced(*stmt.value, " ") : "") + ";" +
               (stmt.step ? spaced(*stmt.step, " ") : "") + ")" + nested(*stmt.body[0]);
      case StmtKind::loop_while:
        return "while (" + spaced(*stmt.value, "") + ")" + nested(*stmt.body[0]);
      case StmtKind::jump:
        return stmt.jump_word + ";";
      case StmtKind::empty:
        return ";";
    }
    return {};
  }

  // The statement of an if, else or loop: on its own line where the template puts it there.
  std::string nested(const Stmt& stmt) const { return spacing(stmt.leading, " ") + statement(stmt); }

  const TargetSyntax& target_;
  const NameMap& names_;
  bool guarded_;
};

void drop_grouping(std::unique_ptr<Expr>& expr) {
  for (auto& operand : expr->operands) drop_grouping(operand);
  if (expr->kind != ExprKind::group) return;
  std::string leading = std::move(expr->leading);
  expr = std::move(expr->operands[0]);
  if (!has_line_break(expr->leading)) expr->leading = std::move(leading);
}

void drop_grouping(Stmt& stmt) {
  for (auto* expr : {&stmt.value, &stmt.step}) {
    if (*expr) drop_grouping(*expr);
  }
  if (stmt.init) drop_grouping(*stmt.init);
  for (auto& inner : stmt.body) drop_grouping(*inner);
}

}  // namespace

void drop_grouping(Body& body) {
  for (auto& stmt : body.statements) drop_grouping(*stmt);
}

std::string print_c_like(const Body& body, const TargetSyntax& target, const NameMap& names, bool guarded) {
  return CLikePrinter(target, names, guarded).body(body);
}

std::string print_c_like(const Expr& expression, const TargetSyntax& target, const NameMap& names, bool guarded) {
  return CLikePrinter(target, names, guarded).expression(expression);
}

}  // namespace saagen::dialect
