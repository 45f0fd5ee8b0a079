// The printer of the typed syntax tree for WGSL. The dialect's C syntax becomes WGSL's where the
// two differ (W3C WGSL, sections cited below); the template's line breaks and comments are kept.
//  - Declarations (7.3, 7.4): `let name: T = v;` for a local the body never reassigns, `var` for
//    the others (the type checker records which); the type is always written.
//  - ?: becomes select(false_value, true_value, condition) (17.3.3): both operands are evaluated,
//    which the dialect allows (its expressions have no side effects).
//  - Branch and loop bodies are always compound statements (9.4, 9.5).
//  - Shift amounts are u32 (8.9): a non-literal int amount is converted.
//  - ++, -- and assignments are statements (9.2, 9.3), never values.
//  - Parameters are immutable (11.1): one the body assigns is copied into a `var`.
//  - && and || are not mixed without parentheses (8.6).
#include "printer_common.hpp"

#include "saagen/error.hpp"
#include "saagen/front/syntax_tree.hpp"
#include "saagen/target/target.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace saagen::dialect {
namespace {

using namespace printing;

bool is_shift(std::string_view op) { return op == "<<" || op == ">>"; }
bool is_logical(std::string_view op) { return op == "&&" || op == "||"; }

// WGSL's grouping: C's, with select() (a call) binding like a primary expression, and && and ||
// never mixed without parentheses.
bool wgsl_needs_parentheses(const Expr& parent, std::size_t position, const Expr& child) {
  if (parent.kind == ExprKind::ternary || child.kind == ExprKind::ternary) return false;
  if (parent.kind == ExprKind::binary && child.kind == ExprKind::binary && is_logical(parent.text) && is_logical(child.text) &&
      parent.text != child.text) {
    return true;
  }
  return needs_parentheses(parent, position, child);
}

// The indentation of a statement: the spaces after the last line break of its layout.
std::string indentation_of(std::string_view layout) {
  const auto last_break = layout.rfind('\n');
  if (last_break == std::string_view::npos) return {};
  const std::string_view line = layout.substr(last_break + 1);
  return std::string(line.substr(0, line.find_first_not_of(" \t")));
}

bool is_reserved(const TargetSyntax& target, std::string_view name) {
  return std::find(target.reserved_words.begin(), target.reserved_words.end(), name) != target.reserved_words.end();
}

std::string local_name(const TargetSyntax& target, const std::string& name) { return is_reserved(target, name) ? name + "_" : name; }

class WgslPrinter {
 public:
  WgslPrinter(const TargetSyntax& target, const PrintOptions& options) : target_(target), options_(options) {}

  std::string body(const Body& body) const {
    std::string out = parameter_copies(body);
    for (const auto& stmt : body.statements) out += stmt->leading + statement(*stmt, indentation_of(stmt->leading));
    return out + body.trailing;
  }

 private:
  // `var x: T = x_in;` for every parameter the body assigns.
  std::string parameter_copies(const Body& body) const {
    if (!options_.signature) return {};
    std::string out;
    for (const auto& [type, name] : options_.signature->parameters) {
      if (std::find(body.assigned_parameters.begin(), body.assigned_parameters.end(), name) == body.assigned_parameters.end()) continue;
      out += fmt::format("    var {}: {} = {};\n", local_name(target_, name), target_.types.at(type.name()),
                         parameter_name(target_, &body, name));
    }
    return out;
  }

  [[noreturn]] static void refuse(const Expr& expr, std::string_view what) {
    throw Error(fmt::format("line {}: {} cannot be a value in WGSL; write it as a statement of its own", expr.line, what));
  }

  std::string name(const std::string& text) const {
    if (options_.names) {
      const auto found = options_.names->find(text);
      if (found != options_.names->end()) return found->second;
    }
    return local_name(target_, text);
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
        if (expr.text == "++" || expr.text == "--") refuse(expr, "'" + expr.text + "'");
        return expr.text + operand(expr, 0, "");
      case ExprKind::postfix:
        refuse(expr, "'" + expr.text + "'");
      case ExprKind::assign:
        refuse(expr, "an assignment");
      case ExprKind::binary:
        return binary(expr);
      case ExprKind::ternary:
        return "select(" + expression(*expr.operands[2]) + "," + spaced(*expr.operands[1], " ") + ", " + expression(*expr.operands[0]) +
               ")";
      case ExprKind::call:
        return call(expr);
      case ExprKind::member:
        return operand(expr, 0, "") + "." + expr.text;
      case ExprKind::index:
        return operand(expr, 0, "") + "[" + spaced(*expr.operands[1], "") + spacing(expr.separators[0], "") + "]";
      case ExprKind::guarded:
        return "(" + expression(*expr.operands[options_.guarded ? 0 : 1]) + ")";
    }
    return {};
  }

  std::string binary(const Expr& expr) const {
    std::string right = operand(expr, 1, " ");
    const Expr& amount = *expr.operands[1];
    if (is_shift(expr.text) && amount.kind != ExprKind::literal) {
      right = spacing(amount.leading, " ") + "u32(" + expression(amount) + ")";
    }
    return operand(expr, 0, "") + spacing(expr.separators[0], " ") + expr.text + right;
  }

  auto printer() const {
    return [this](const Expr& expr) { return expression(expr); };
  }
  std::string operand(const Expr& parent, std::size_t position, std::string_view canonical) const {
    return operand_text(parent, position, canonical, printer(), wgsl_needs_parentheses);
  }
  std::string spaced(const Expr& expr, std::string_view canonical) const { return spaced_text(expr, canonical, printer()); }
  std::string arguments(const Expr& expr) const { return arguments_text(expr, printer()); }

  std::string call(const Expr& expr) const {
    if (expr.call_kind == CallKind::intrinsic) {
      const auto pattern = target_.intrinsics.find(expr.text);
      if (pattern != target_.intrinsics.end()) {
        std::vector<std::string> values;
        for (const auto& argument : expr.operands) values.push_back(expression(*argument));
        std::string typed = substitute(pattern->second, "{type}", target_.types.at(expr.type.name()));
        typed = substitute(std::move(typed), "{wide_type}", target_.wide_types.at(expr.type.name()));
        return expand_pattern(typed, values);
      }
      return expr.text + "(" + arguments(expr) + spacing(expr.separators[0], "") + ")";
    }
    if (expr.call_kind == CallKind::constructor)
      return target_.types.at(expr.text) + "(" + arguments(expr) + spacing(expr.separators[0], "") + ")";
    std::string extra;
    if (options_.call_arguments) {
      const auto found = options_.call_arguments->find(expr.text);
      if (found != options_.call_arguments->end()) extra = (expr.operands.empty() ? "" : ", ") + found->second;
    }
    return name(expr.text) + "(" + arguments(expr) + extra + spacing(expr.separators[0], "") + ")";
  }

  // An expression statement: assignments, increments and calls as WGSL writes them; any other
  // value is discarded through the phony assignment `_ = value` (9.2.1).
  std::string effect(const Expr& expr) const {
    switch (expr.kind) {
      case ExprKind::assign:
        return expression(*expr.operands[0]) + spacing(expr.separators[0], " ") + expr.text + spaced(*expr.operands[1], " ");
      case ExprKind::unary:
        if (expr.text == "++" || expr.text == "--") return expression(*expr.operands[0]) + expr.text;
        break;
      case ExprKind::postfix:
        return expression(*expr.operands[0]) + expr.text;
      case ExprKind::call:
        if (expr.call_kind == CallKind::function) return expression(expr);
        break;
      default:
        break;
    }
    return "_ = " + expression(expr);
  }

  std::string declaration(const Stmt& stmt) const {
    const std::string type = target_.types.at(stmt.type_name);
    const bool variable = stmt.is_mutable || !stmt.value;
    return fmt::format("{} {}: {}", variable ? "var" : "let", local_name(target_, stmt.name), type) +
           (stmt.value ? " =" + spaced(*stmt.value, " ") : "");
  }

  // A statement without its leading layout; `indent` is its line's indentation.
  std::string statement(const Stmt& stmt, const std::string& indent) const {
    switch (stmt.kind) {
      case StmtKind::declaration:
        return declaration(stmt) + ";";
      case StmtKind::expression:
        return effect(*stmt.value) + ";";
      case StmtKind::return_value:
        return "return" + (stmt.value ? spaced(*stmt.value, " ") : "") + ";";
      case StmtKind::conditional: {
        std::string out = "if " + spaced(*stmt.value, "") + compound(*stmt.body[0], indent);
        if (stmt.body.size() == 2) {
          const Stmt& otherwise = *stmt.body[1];
          out += spacing(stmt.closing, " ") + "else";
          out += otherwise.kind == StmtKind::conditional ? " " + statement(otherwise, indent) : compound(otherwise, indent);
        }
        return out;
      }
      case StmtKind::block:
        return block(stmt, indent);
      case StmtKind::loop_for:
        return "for (" + (stmt.init->kind == StmtKind::declaration ? declaration(*stmt.init) : effect(*stmt.init->value)) + ";" +
               (stmt.value ? spaced(*stmt.value, " ") : "") + ";" +
               (stmt.step ? spacing(stmt.step->leading, " ") + effect(*stmt.step) : "") + ")" + compound(*stmt.body[0], indent);
      case StmtKind::loop_while:
        return "while " + spaced(*stmt.value, "") + compound(*stmt.body[0], indent);
      case StmtKind::jump:
        return stmt.jump_word + ";";
      case StmtKind::empty:
        return ";";
    }
    return {};
  }

  std::string block(const Stmt& stmt, const std::string& indent) const {
    std::string out = "{";
    for (const auto& inner : stmt.body) {
      const std::string inner_indent = has_line_break(inner->leading) ? indentation_of(inner->leading) : indent;
      out += inner->leading + statement(*inner, inner_indent);
    }
    return out + stmt.closing + "}";
  }

  // The body of an if, else or loop as a compound statement: a block as written, any other
  // statement inside braces, on its own line where the template puts it there.
  std::string compound(const Stmt& stmt, const std::string& indent) const {
    if (stmt.kind == StmtKind::block) return " " + block(stmt, indent);
    if (has_line_break(stmt.leading)) return " {" + stmt.leading + statement(stmt, indentation_of(stmt.leading)) + "\n" + indent + "}";
    return " { " + statement(stmt, indent) + " }";
  }

  const TargetSyntax& target_;
  const PrintOptions& options_;
};

}  // namespace

std::string parameter_name(const TargetSyntax& target, const Body* body, const std::string& name) {
  const bool copied =
      target.copies_assigned_parameters() && body &&
      std::find(body->assigned_parameters.begin(), body->assigned_parameters.end(), name) != body->assigned_parameters.end();
  return local_name(target, name) + (copied ? "_in" : "");
}

std::string print_wgsl(const Body& body, const TargetSyntax& target, const PrintOptions& options) {
  return WgslPrinter(target, options).body(body);
}

}  // namespace saagen::dialect
