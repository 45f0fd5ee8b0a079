// The dialect's types, its intrinsic table (templates/intrinsics.sig) and the load-time type
// checker of template bodies (saagen/front/syntax_tree.hpp). The rules are those the C-like targets
// and WGSL share: no implicit conversion between real, int and bool; a real scalar combines
// with a real vector in + - * / (component-wise); a call matches one signature exactly.
#include "saagen/error.hpp"
#include "saagen/front/syntax_tree.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <functional>
#include <sstream>

namespace saagen {
namespace embedded {
const std::map<std::string, std::string_view>& files();
}

namespace dialect {

std::optional<Type> Type::from_name(std::string_view name) {
  if (name == "real") return Type::real();
  if (name == "real2") return Type::real(2);
  if (name == "real3") return Type::real(3);
  if (name == "real4") return Type::real(4);
  if (name == "int") return Type::integer();
  if (name == "bool") return Type::boolean();
  return std::nullopt;
}

std::string Type::name() const {
  switch (base) {
    case Base::real:
      return size == 1 ? "real" : fmt::format("real{}", size);
    case Base::integer:
      return "int";
    case Base::boolean:
      return "bool";
    case Base::none:
      break;
  }
  return "nothing";
}

// ---------------------------------------------------------------------------------------------
// The intrinsic table

namespace {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  for (std::size_t begin = 0;;) {
    const auto end = text.find(separator, begin);
    parts.push_back(trim(text.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin)));
    if (end == std::string_view::npos) return parts;
    begin = end + 1;
  }
}

// Expands one line's type variable F into its four real types.
std::vector<IntrinsicSignature> parse_signature_line(std::string_view text, std::string_view source, int line) {
  const auto fail = [&](std::string_view why) -> std::vector<IntrinsicSignature> {
    throw Error(fmt::format("{}:{}: {}; write RESULT NAME(TYPE, ...) [derivative] [resource NAME]", source, line, why));
  };
  const auto open = text.find('('), close = text.find(')');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open) return fail("expected a signature");
  const auto head = split(trim(text.substr(0, open)), ' ');
  if (head.size() != 2) return fail("expected the result type and the name before '('");
  std::vector<std::string_view> parameter_names;
  if (!trim(text.substr(open + 1, close - open - 1)).empty()) parameter_names = split(text.substr(open + 1, close - open - 1), ',');
  std::istringstream flags{std::string(text.substr(close + 1))};
  bool derivative = false;
  std::string resource;
  for (std::string flag; flags >> flag;) {
    if (flag == "derivative")
      derivative = true;
    else if (flag == "resource" && flags >> resource)
      continue;
    else
      return fail(fmt::format("unknown flag '{}'", flag));
  }
  const bool generic = head[0] == "F" || std::find(parameter_names.begin(), parameter_names.end(), "F") != parameter_names.end();
  std::vector<IntrinsicSignature> signatures;
  for (int size = 1; size <= (generic ? 4 : 1); ++size) {
    const auto resolve = [&](std::string_view name) {
      if (name == "F") return Type::real(size);
      const auto type = Type::from_name(name);
      if (!type) fail(fmt::format("unknown type '{}'", name));
      return *type;
    };
    IntrinsicSignature signature{std::string(head[1]), resolve(head[0]), {}, derivative, resource};
    for (std::string_view parameter : parameter_names) signature.parameters.push_back(resolve(parameter));
    signatures.push_back(std::move(signature));
  }
  return signatures;
}

}  // namespace

std::vector<IntrinsicSignature> parse_intrinsics(std::string_view text, std::string_view source_name) {
  std::vector<IntrinsicSignature> table;
  int line = 0;
  for (std::string_view row : split(text, '\n')) {
    ++line;
    if (row.empty() || row.front() == '#') continue;
    for (IntrinsicSignature& signature : parse_signature_line(row, source_name, line)) table.push_back(std::move(signature));
  }
  return table;
}

const std::vector<IntrinsicSignature>& intrinsics() {
  static const std::vector<IntrinsicSignature> table = [] {
    const auto& files = embedded::files();
    const auto found = files.find("templates/intrinsics.sig");
    if (found == files.end()) throw Error("templates/intrinsics.sig is not embedded in this build; rebuild saagen");
    return parse_intrinsics(found->second, found->first);
  }();
  return table;
}

namespace {

// The overloads of each intrinsic, by name.
using IntrinsicIndex = std::map<std::string, std::vector<const IntrinsicSignature*>, std::less<>>;

IntrinsicIndex index_by_name(const std::vector<IntrinsicSignature>& table) {
  IntrinsicIndex index;
  for (const IntrinsicSignature& signature : table) index[signature.name].push_back(&signature);
  return index;
}

const IntrinsicIndex& builtin_index() {
  static const IntrinsicIndex index = index_by_name(intrinsics());
  return index;
}

}  // namespace

bool is_intrinsic(std::string_view name) { return builtin_index().count(name) > 0; }

bool is_derivative_intrinsic(std::string_view name) {
  const auto found = builtin_index().find(name);
  return found != builtin_index().end() &&
         std::any_of(found->second.begin(), found->second.end(), [](const IntrinsicSignature* s) { return s->derivative; });
}

// ---------------------------------------------------------------------------------------------
// The checker

namespace {

std::string describe_types(const std::vector<Type>& types) {
  std::string text;
  for (const Type& type : types) text += (text.empty() ? "" : ", ") + type.name();
  return text;
}

bool is_arithmetic(std::string_view op) { return op == "+" || op == "-" || op == "*" || op == "/"; }
bool is_bitwise(std::string_view op) { return op == "%" || op == "&" || op == "|" || op == "^" || op == "<<" || op == ">>"; }
bool is_ordering(std::string_view op) { return op == "<" || op == ">" || op == "<=" || op == ">="; }
bool is_equality(std::string_view op) { return op == "==" || op == "!="; }
bool is_logical(std::string_view op) { return op == "&&" || op == "||"; }

class Checker {
 public:
  Checker(const FunctionSignature& signature, const CheckContext& context, const SourcePlace& place)
      : signature_(signature),
        context_(context),
        place_(place),
        own_index_(context.intrinsics ? index_by_name(*context.intrinsics) : IntrinsicIndex()),
        intrinsics_(context.intrinsics ? own_index_ : builtin_index()) {}

  void check(Body& body) {
    scopes_.emplace_back();
    for (const auto& [type, name] : signature_.parameters) scopes_.back()[name] = Local{type, nullptr};
    for (auto& stmt : body.statements) statement(*stmt);
    // A body without a result (harness glue) has no return to check.
    if (!signature_.result.is_none() &&
        !std::any_of(body.statements.begin(), body.statements.end(), [](const auto& stmt) { return always_returns(*stmt); })) {
      fail(body.statements.empty() ? place_.first_line : body.statements.back()->line,
           fmt::format("the body can end without returning {}; end every path with a return", signature_.result.name()));
    }
    scopes_.pop_back();
  }

 private:
  struct Local {
    Type type;
    Stmt* declaration;  // null for a parameter
  };

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw Error(fmt::format("{}:{}: {}: {}", place_.file, line, place_.function, message));
  }

  static bool always_returns(const Stmt& stmt) {
    switch (stmt.kind) {
      case StmtKind::return_value:
        return true;
      case StmtKind::block:
        return std::any_of(stmt.body.begin(), stmt.body.end(), [](const auto& inner) { return always_returns(*inner); });
      case StmtKind::conditional:
        return stmt.body.size() == 2 && always_returns(*stmt.body[0]) && always_returns(*stmt.body[1]);
      default:
        return false;
    }
  }

  const Local* find_local(std::string_view name) const {
    for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope) {
      const auto found = scope->find(name);
      if (found != scope->end()) return &found->second;
    }
    return nullptr;
  }

  void statement(Stmt& stmt) {
    switch (stmt.kind) {
      case StmtKind::declaration:
        declaration(stmt);
        break;
      case StmtKind::expression:
        expression(*stmt.value);
        break;
      case StmtKind::return_value:
        return_value(stmt);
        break;
      case StmtKind::conditional:
        condition(*stmt.value, "if");
        for (auto& branch : stmt.body) scoped(*branch);
        break;
      case StmtKind::block:
        scopes_.emplace_back();
        for (auto& inner : stmt.body) statement(*inner);
        scopes_.pop_back();
        break;
      case StmtKind::loop_for:
        scopes_.emplace_back();
        statement(*stmt.init);
        if (stmt.value) condition(*stmt.value, "for");
        if (stmt.step) expression(*stmt.step);
        ++loop_depth_;
        scoped(*stmt.body[0]);
        --loop_depth_;
        scopes_.pop_back();
        break;
      case StmtKind::loop_while:
        condition(*stmt.value, "while");
        ++loop_depth_;
        scoped(*stmt.body[0]);
        --loop_depth_;
        break;
      case StmtKind::jump:
        if (loop_depth_ == 0) fail(stmt.line, fmt::format("'{}' outside a loop; remove it", stmt.jump_word));
        break;
      case StmtKind::empty:
        break;
    }
  }

  void scoped(Stmt& stmt) {
    scopes_.emplace_back();
    statement(stmt);
    scopes_.pop_back();
  }

  void declaration(Stmt& stmt) {
    const Type type = *Type::from_name(stmt.type_name);
    if (find_local(stmt.name) || (context_.constants && context_.constants->count(stmt.name)) ||
        (context_.functions && context_.functions->count(stmt.name)) || Type::from_name(stmt.name) || is_known_intrinsic(stmt.name)) {
      fail(stmt.line,
           fmt::format("'{}' is already declared (a parameter, local, constant, function or intrinsic); choose another name", stmt.name));
    }
    if (stmt.value) {
      const Type value = expression(*stmt.value);
      if (value != type) {
        fail(stmt.value->line, fmt::format("'{}' is declared {} but initialised with a {}; convert explicitly ({}(...)) or fix the type",
                                           stmt.name, type.name(), value.name(), type.name()));
      }
    }
    scopes_.back()[stmt.name] = Local{type, &stmt};
  }

  void return_value(Stmt& stmt) {
    if (!stmt.value) fail(stmt.line, fmt::format("return needs a value of type {}", signature_.result.name()));
    const Type type = expression(*stmt.value);
    if (type != signature_.result) {
      fail(stmt.value->line,
           fmt::format("returns {} but the function is declared 'returns: {}'; convert explicitly or fix the 'returns:' line", type.name(),
                       signature_.result.name()));
    }
  }

  void condition(Expr& expr, std::string_view statement_word) {
    const Type type = expression(expr);
    if (type != Type::boolean()) {
      fail(expr.line, fmt::format("the condition of '{}' is {}, not bool; compare it (e.g. x > 0.0)", statement_word, type.name()));
    }
  }

  Type expression(Expr& expr) {
    expr.type = type_of(expr);
    return expr.type;
  }

  Type type_of(Expr& expr) {
    switch (expr.kind) {
      case ExprKind::literal:
        return literal(expr);
      case ExprKind::name:
        return name(expr);
      case ExprKind::group:
        return expression(*expr.operands[0]);
      case ExprKind::unary:
        return expr.text == "++" || expr.text == "--" ? step(expr) : unary(expr);
      case ExprKind::postfix:
        return step(expr);
      case ExprKind::binary:
        return binary(expr);
      case ExprKind::ternary:
        return ternary(expr);
      case ExprKind::call:
        return call(expr);
      case ExprKind::member:
        return member(expr);
      case ExprKind::index:
        return index(expr);
      case ExprKind::assign:
        return assign(expr);
      case ExprKind::guarded:
        return guarded(expr);
    }
    return {};
  }

  Type literal(const Expr& expr) const {
    if (expr.text == "true" || expr.text == "false") return Type::boolean();
    const bool is_real = expr.text.find_first_of(".eE") != std::string::npos;
    const bool plain = std::all_of(expr.text.begin(), expr.text.end(), [&](char c) {
      return std::isdigit(static_cast<unsigned char>(c)) || (is_real && (c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'));
    });
    if (!plain || expr.text.starts_with("0x")) {
      fail(expr.line,
           fmt::format(
               "'{}' is not a dialect number; write decimal numbers without suffixes (2.0, 1e-4, 3): the emitter adds precision suffixes",
               expr.text));
    }
    return is_real ? Type::real() : Type::integer();
  }

  Type name(const Expr& expr) const {
    if (const Local* local = find_local(expr.text)) return local->type;
    if (context_.constants) {
      const auto constant = context_.constants->find(expr.text);
      if (constant != context_.constants->end()) return constant->second;
    }
    if ((context_.functions && context_.functions->count(expr.text)) || is_known_intrinsic(expr.text)) {
      fail(expr.line, fmt::format("'{}' is a function; call it with its arguments", expr.text));
    }
    fail(expr.line, fmt::format("'{}' is not declared; declare it (TYPE {} = ...) before its use, or name a parameter or a constant",
                                expr.text, expr.text));
  }

  bool is_known_intrinsic(std::string_view name) const { return intrinsics_.count(name) > 0; }

  Type unary(Expr& expr) {
    const Type operand = expression(*expr.operands[0]);
    const bool fits = expr.text == "!"   ? operand == Type::boolean()
                      : expr.text == "~" ? operand == Type::integer()
                                         : operand.base == Type::Base::real || operand == Type::integer();
    if (!fits) fail(expr.line, fmt::format("unary '{}' does not apply to {}; convert the operand explicitly", expr.text, operand.name()));
    return operand;
  }

  // ++x, x++, --x, x--: an int or real variable, which becomes mutable.
  Type step(Expr& expr) {
    const Type type = expression(*expr.operands[0]);
    mark_assigned(expr, *expr.operands[0]);
    if (type != Type::integer() && type != Type::real()) {
      fail(expr.line, fmt::format("'{}' needs an int or real variable, not {}", expr.text, type.name()));
    }
    return type;
  }

  // Records that `target` (a variable, or a swizzle of one) is assigned.
  void mark_assigned(const Expr& expr, Expr& target_expression) {
    Expr* target = &target_expression;
    while (target->kind == ExprKind::member) target = target->operands[0].get();
    if (target->kind != ExprKind::name) fail(expr.line, fmt::format("'{}' assigns to something that is not a variable", expr.text));
    const Local* local = find_local(target->text);
    if (!local) fail(expr.line, fmt::format("'{}' is not a local or a parameter; only those can be assigned", target->text));
    if (local->declaration)
      local->declaration->is_mutable = true;
    else if (std::find(assigned_parameters_.begin(), assigned_parameters_.end(), target->text) == assigned_parameters_.end()) {
      assigned_parameters_.push_back(target->text);
    }
  }

  Type binary(Expr& expr) {
    const Type left = expression(*expr.operands[0]);
    const Type right = expression(*expr.operands[1]);
    const std::string_view op = expr.text;
    const auto refuse = [&](std::string_view what_to_do) -> Type {
      fail(expr.line, fmt::format("'{}' between {} and {}: {}", op, left.name(), right.name(), what_to_do));
    };
    if (is_arithmetic(op)) {
      if (left == Type::integer() && right == Type::integer()) return left;
      if (left.base == Type::Base::real && right.base == Type::Base::real) {
        if (left == right || right.is_scalar()) return left;
        if (left.is_scalar()) return right;
        return refuse("the vector sizes differ; take a swizzle or build the matching vector");
      }
      return refuse("the dialect converts nothing implicitly; write real(...) or int(...)");
    }
    if (is_bitwise(op)) {
      if (left == Type::integer() && right == Type::integer()) return left;
      return refuse("integer operators need int operands; convert with int(...)");
    }
    if (is_ordering(op) || is_equality(op)) {
      if (left != right) return refuse("compare values of one type; convert one side explicitly");
      if (!left.is_scalar()) return refuse("compare scalars; take a component (v.x)");
      if (is_ordering(op) && left == Type::boolean()) return refuse("bool values have no order");
      return Type::boolean();
    }
    if (is_logical(op)) {
      if (left == Type::boolean() && right == Type::boolean()) return left;
      return refuse("logical operators take bool operands; compare first (x > 0.0)");
    }
    return refuse("unknown operator");
  }

  Type ternary(Expr& expr) {
    condition(*expr.operands[0], "?:");
    const Type when_true = expression(*expr.operands[1]);
    const Type when_false = expression(*expr.operands[2]);
    if (when_true != when_false) {
      fail(expr.line, fmt::format("the branches of '?:' are {} and {}; convert one explicitly so that both have one type", when_true.name(),
                                  when_false.name()));
    }
    return when_true;
  }

  std::vector<Type> arguments(Expr& expr) {
    std::vector<Type> types;
    for (auto& operand : expr.operands) types.push_back(expression(*operand));
    return types;
  }

  Type call(Expr& expr) {
    const std::vector<Type> types = arguments(expr);
    if (const auto type = Type::from_name(expr.text)) {
      expr.call_kind = CallKind::constructor;
      return constructor(expr, *type, types);
    }
    if (context_.functions) {
      const auto function = context_.functions->find(expr.text);
      if (function != context_.functions->end()) {
        expr.call_kind = CallKind::function;
        std::vector<Type> expected;
        for (const auto& parameter : function->second.parameters) expected.push_back(parameter.first);
        if (types != expected) {
          fail(expr.line, fmt::format("{} takes ({}) but is called with ({}); convert the arguments explicitly", expr.text,
                                      describe_types(expected), describe_types(types)));
        }
        return function->second.result;
      }
    }
    if (!is_known_intrinsic(expr.text)) {
      fail(expr.line, fmt::format("unknown function '{}': neither a template function nor a dialect intrinsic "
                                  "(templates/intrinsics.sig); define it with @function or fix the name",
                                  expr.text));
    }
    expr.call_kind = CallKind::intrinsic;
    std::vector<std::string> offered;
    for (const IntrinsicSignature* signature : intrinsics_.find(expr.text)->second) {
      if (signature->parameters == types) return signature->result;
      offered.push_back(fmt::format("({})", describe_types(signature->parameters)));
    }
    fail(expr.line, fmt::format("no {} takes ({}); it takes {}; convert the arguments explicitly", expr.text, describe_types(types),
                                fmt::join(offered, " or ")));
  }

  // real(x), int(x), bool(x): one scalar of any type. realN(...): one realN, or real scalars and
  // vectors whose components add up to N (no int: convert it first).
  Type constructor(const Expr& expr, Type type, const std::vector<Type>& types) const {
    if (type.is_scalar()) {
      if (types.size() != 1 || !types[0].is_scalar()) {
        fail(expr.line, fmt::format("{}(...) converts one scalar, not ({})", type.name(), describe_types(types)));
      }
      return type;
    }
    if (types.size() == 1 && types[0] == type) return type;
    int components = 0;
    for (const Type& argument : types) {
      if (argument.base != Type::Base::real) {
        fail(expr.line, fmt::format("{}(...) takes real components, not {}; convert it with real(...)", type.name(), argument.name()));
      }
      components += argument.size;
    }
    if (components != type.size) {
      fail(expr.line, fmt::format("{}(...) needs {} components but ({}) give {}; list every component (HLSL does not splat one scalar)",
                                  type.name(), type.size, describe_types(types), components));
    }
    return type;
  }

  Type member(Expr& expr) {
    const Type object = expression(*expr.operands[0]);
    if (object.base != Type::Base::real || object.is_scalar()) {
      fail(expr.line, fmt::format("'.{}' needs a real vector, not {}", expr.text, object.name()));
    }
    static const std::string_view sets[] = {"xyzw", "rgba"};
    const auto valid_in = [&](std::string_view set) {
      return std::all_of(expr.text.begin(), expr.text.end(), [&](char c) {
        const auto position = set.find(c);
        return position != std::string_view::npos && static_cast<int>(position) < object.size;
      });
    };
    if (expr.text.size() > 4 || !(valid_in(sets[0]) || valid_in(sets[1]))) {
      fail(expr.line, fmt::format("'.{}' is not a swizzle of a {}; use x, y, z, w (up to the vector's size)", expr.text, object.name()));
    }
    return Type::real(static_cast<int>(expr.text.size()));
  }

  Type index(Expr& expr) {
    const Type object = expression(*expr.operands[0]);
    const Type position = expression(*expr.operands[1]);
    if (object.base != Type::Base::real || object.is_scalar() || position != Type::integer()) {
      fail(expr.line, fmt::format("indexing needs a real vector and an int, not {} and {}", object.name(), position.name()));
    }
    return Type::real();
  }

  Type assign(Expr& expr) {
    mark_assigned(expr, *expr.operands[0]);
    const Type assigned = expression(*expr.operands[0]);
    const Type value = expression(*expr.operands[1]);
    const std::string_view op = std::string_view(expr.text).substr(0, expr.text.size() - 1);
    const bool fits = op.empty()          ? value == assigned
                      : is_arithmetic(op) ? (value == assigned || (assigned.base == Type::Base::real && value == Type::real()))
                                          : (assigned == Type::integer() && value == Type::integer());
    if (!fits) {
      fail(expr.line, fmt::format("'{}' assigns a {} to a {}; convert explicitly ({}(...))", expr.text, value.name(), assigned.name(),
                                  assigned.name()));
    }
    return assigned;
  }

  Type guarded(Expr& expr) {
    const Type safe = expression(*expr.operands[0]);
    const Type paper = expression(*expr.operands[1]);
    if (safe != paper) {
      fail(expr.line,
           fmt::format("guarded(safe, paper) has a {} safe form and a {} paper form; both must have one type", safe.name(), paper.name()));
    }
    return safe;
  }

  const FunctionSignature& signature_;
  const CheckContext& context_;
  const SourcePlace& place_;
  const IntrinsicIndex own_index_;
  const IntrinsicIndex& intrinsics_;
  std::vector<std::map<std::string, Local, std::less<>>> scopes_;
  int loop_depth_ = 0;

 public:
  std::vector<std::string> assigned_parameters_;
};

void collect_names(const Expr& expr, std::optional<bool> guarded, std::vector<std::string>& names) {
  if (expr.kind == ExprKind::name || expr.kind == ExprKind::call || (expr.kind == ExprKind::guarded && !guarded))
    names.push_back(expr.text);
  if (expr.kind == ExprKind::guarded && guarded) {
    collect_names(*expr.operands[*guarded ? 0 : 1], guarded, names);
    return;
  }
  for (const auto& operand : expr.operands) collect_names(*operand, guarded, names);
}

void collect_names(const Stmt& stmt, std::optional<bool> guarded, std::vector<std::string>& names) {
  if (stmt.init) collect_names(*stmt.init, guarded, names);
  if (stmt.value) collect_names(*stmt.value, guarded, names);
  if (stmt.step) collect_names(*stmt.step, guarded, names);
  for (const auto& inner : stmt.body) collect_names(*inner, guarded, names);
}

}  // namespace

void check_body(Body& body, const FunctionSignature& signature, const CheckContext& context, const SourcePlace& place) {
  Checker checker(signature, context, place);
  checker.check(body);
  body.assigned_parameters = std::move(checker.assigned_parameters_);
}

std::vector<std::string> referenced_names(const Body& body, std::optional<bool> guarded) {
  std::vector<std::string> names;
  for (const auto& stmt : body.statements) collect_names(*stmt, guarded, names);
  return names;
}

}  // namespace dialect
}  // namespace saagen
