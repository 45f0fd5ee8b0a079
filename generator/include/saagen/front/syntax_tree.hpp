// The typed syntax tree of a template function body (templates/README.md, "The dialect"): the
// parser, the type checker that refuses a body at load time, and the printer of C-like target
// languages. Printing is driven by a target's syntax table (saagen/target/target.hpp); the tree carries
// what other language families need as well: the type of every expression, every local's
// mutability, the source's grouping parentheses, and the layout (line breaks, comments) of the
// template so that a C-like printer reproduces it.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {
struct TargetSyntax;
}

namespace saagen::dialect {

// A value type of the dialect: real, real2..real4, int or bool (no matrices).
struct Type {
  enum class Base { real, integer, boolean, none };
  Base base = Base::none;
  int size = 1;  // vector width, 1 for scalars

  static Type real(int size = 1) { return {Base::real, size}; }
  static Type integer() { return {Base::integer, 1}; }
  static Type boolean() { return {Base::boolean, 1}; }
  static std::optional<Type> from_name(std::string_view name);  // "real3" -> real x 3
  std::string name() const;                                     // the dialect's spelling
  bool is_none() const { return base == Base::none; }
  bool is_scalar() const { return size == 1; }
  friend bool operator==(const Type&, const Type&) = default;
};

enum class ExprKind {
  literal,  // text: the number as written
  name,     // text: a local, a parameter or a template constant
  group,    // (operand): parentheses written in the template
  unary,    // text: - ! ~ ++ -- (prefix)
  postfix,  // text: ++ or -- after operand 0
  binary,   // text: the operator
  ternary,  // condition ? operand 1 : operand 2
  call,     // text: the callee; operands: the arguments
  member,   // text: the swizzle (xy, z, ...)
  index,    // operand 0 [operand 1]
  assign,   // text: = += -= *= /= ...; operand 0 is the assigned name
  guarded,  // guarded(safe, paper): the emission chooses one (operands 0 and 1)
};

enum class CallKind { function, intrinsic, constructor };

struct Expr {
  ExprKind kind = ExprKind::literal;
  std::string text;
  std::vector<std::unique_ptr<Expr>> operands;
  // Layout: the whitespace and comments before this expression's first token, and before the
  // tokens inside it that separate operands (binary: the operator; ternary: '?' and ':';
  // call and group: the closing ')'; index: ']'). A C-like printer keeps line breaks only.
  std::string leading;
  std::vector<std::string> separators;
  int line = 0;
  // Set by the type checker.
  Type type;
  CallKind call_kind = CallKind::function;
};

enum class StmtKind { declaration, expression, return_value, conditional, block, loop_for, loop_while, jump, empty };

struct Stmt {
  StmtKind kind = StmtKind::empty;
  std::string leading;  // whitespace and comments before the statement, printed as written
  int line = 0;
  // declaration: `type name = value;` (value optional)
  std::string type_name;
  std::string name;
  bool is_mutable = false;  // set by the type checker: the local is assigned after its declaration
  // declaration: value; expression: the expression; return_value: the value (optional);
  // conditional / loops: the condition; loop_for: also the step (expressions[1], optional).
  std::unique_ptr<Expr> value;
  std::unique_ptr<Expr> step;
  // conditional: then (body[0]) and else (body[1], optional); loops: body[0]; loop_for: the
  // initialiser in `init`; block: its statements.
  std::vector<std::unique_ptr<Stmt>> body;
  std::unique_ptr<Stmt> init;
  std::string closing;    // block: the layout before '}'; conditional: before `else`
  std::string jump_word;  // jump: break or continue
};

struct Body {
  std::vector<std::unique_ptr<Stmt>> statements;
  std::string trailing;  // the layout after the last statement
  // Set by the type checker: parameters the body assigns (WGSL parameters are immutable).
  std::vector<std::string> assigned_parameters;
};

// Where a body comes from, for "file:line: function: ..." diagnostics.
struct SourcePlace {
  std::string file;
  int first_line = 1;  // the line of the body's first character
  std::string function;
};

// Parses a function body; throws saagen::Error "file:line: function: what; what to do".
Body parse_body(std::string_view code, const SourcePlace& place);

// A signature of a dialect intrinsic (templates/intrinsics.sig).
struct IntrinsicSignature {
  std::string name;
  Type result;
  std::vector<Type> parameters;
  bool derivative = false;  // takes screen-space derivatives: fragment-only
  std::string resource;     // the resource it reads, or empty
};

// The intrinsic table compiled into this build, and its parser (one signature a line).
const std::vector<IntrinsicSignature>& intrinsics();
std::vector<IntrinsicSignature> parse_intrinsics(std::string_view text, std::string_view source_name);
bool is_intrinsic(std::string_view name);
bool is_derivative_intrinsic(std::string_view name);

// What the checker knows besides the body: the function's signature, the other template
// functions and the constants.
struct FunctionSignature {
  Type result;
  std::vector<std::pair<Type, std::string>> parameters;
};
struct CheckContext {
  const std::map<std::string, FunctionSignature, std::less<>>* functions = nullptr;
  const std::map<std::string, Type, std::less<>>* constants = nullptr;
  const std::vector<IntrinsicSignature>* intrinsics = nullptr;  // null: intrinsics()
};

// Types every expression, marks assigned locals mutable (a signature whose result is none checks a
// body of statements that returns nothing, such as harness glue), and refuses (saagen::Error, "file:line:
// function: what; what to do") a body that mixes types without a conversion, calls an unknown
// function, uses an undeclared name or returns a value of the wrong type.
void check_body(Body& body, const FunctionSignature& signature, const CheckContext& context, const SourcePlace& place);

// Every name the body references outside member accesses, in source order, with guards resolved
// as `guarded` says (both arguments when nullopt); callees included.
std::vector<std::string> referenced_names(const Body& body, std::optional<bool> guarded);

// Removes the parentheses the template wrote (group nodes): what remains is the tree's own
// structure, from which a printer adds exactly the parentheses that precedence requires.
void drop_grouping(Body& body);

// Maps unprefixed template names (functions, constants) to the names they get in the output.
using NameMap = std::map<std::string, std::string, std::less<>>;

// Prints a body in a C-like target language (GLSL, HLSL, GLSL ES) from its syntax table: types
// and intrinsic patterns from the table, template names through `names`, guards resolved to the
// safe (`guarded`) or the paper form. The template's layout and comments are kept.
std::string print_c_like(const Body& body, const TargetSyntax& target, const NameMap& names, bool guarded);
// One expression, without its leading layout.
std::string print_c_like(const Expr& expression, const TargetSyntax& target, const NameMap& names, bool guarded);

// What printing a body needs besides the tree and the target's table.
struct PrintOptions {
  const NameMap* names = nullptr;  // template names -> emitted names
  bool guarded = true;             // guards resolved to the safe form (else the paper form)
  // Arguments appended to the calls of a template function (unprefixed name -> text), in a module
  // language: the resources the callee reads (TargetSyntax::Resource).
  const std::map<std::string, std::string, std::less<>>* call_arguments = nullptr;
  // The function's signature, when the body is a function's: a module language copies the
  // parameters the body assigns into locals (WGSL parameters are immutable). Null for glue,
  // whose free names are the skeleton's variables.
  const FunctionSignature* signature = nullptr;
};

// Prints a body in WGSL: `let` for locals never reassigned and `var` for the others, every
// declaration typed, `select` for ?:, braces around every branch and loop body, shift amounts
// converted to u32, and locals or parameters called like a reserved word renamed (a trailing '_').
// Increments and assignments print as statements only (WGSL has no such expressions); a template
// that uses one as a value is refused with saagen::Error.
std::string print_wgsl(const Body& body, const TargetSyntax& target, const PrintOptions& options);
// The body in the target's language (TargetSyntax::language).
std::string print_body(const Body& body, const TargetSyntax& target, const PrintOptions& options);
// The name a parameter has in a signature printed for `target`: renamed when it is a reserved
// word, and suffixed "_in" where a module language copies it into a mutable local.
std::string parameter_name(const TargetSyntax& target, const Body* body, const std::string& name);

}  // namespace saagen::dialect
