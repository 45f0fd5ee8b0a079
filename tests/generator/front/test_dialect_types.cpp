// The typed dialect: the parser and type checker refuse each class of mistake at load time with
// file:line and what to do; the C-like printer reproduces a template and adds exactly the
// parentheses precedence needs; the tree carries types and mutability for other printers.
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/front/syntax_tree.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/target/target.hpp"

#include <gtest/gtest.h>

namespace {

using saagen::Catalogue;
namespace dialect = saagen::dialect;

// A one-function template whose body starts at line 7.
std::string function_template(const std::string& returns, const std::string& body) {
  return "@function f\nrole: core\ncite: c\nreturns: " + returns + " | r\nparam: real x | x\n{\n" + body + "}\n";
}

std::string load_error(const std::string& text) {
  try {
    Catalogue::parse({{"templates/test.saa", text}});
  } catch (const saagen::Error& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(DialectTypes, RefusesMixedTypesWithoutAConversion) {
  EXPECT_EQ(load_error(function_template("real", "    return x + 1;\n")),
            "templates/test.saa:7: f: '+' between real and int: the dialect converts nothing implicitly; write real(...) or int(...)");
  EXPECT_EQ(load_error(function_template("real2", "    real2 v = real2(x, x);\n    return v + real3(x, x, x);\n")),
            "templates/test.saa:8: f: '+' between real2 and real3: the vector sizes differ; take a swizzle or build the matching vector");
  EXPECT_EQ(load_error(function_template("real", "    int n = x;\n    return x;\n")),
            "templates/test.saa:7: f: 'n' is declared int but initialised with a real; convert explicitly (int(...)) or fix the type");
  EXPECT_EQ(load_error(function_template("real", "    return x < 1 ? x : 0.0;\n")),
            "templates/test.saa:7: f: '<' between real and int: compare values of one type; convert one side explicitly");
  // GLSL would splat real2(x); HLSL and WGSL do not, so the dialect does not either.
  EXPECT_EQ(
      load_error(function_template("real2", "    return real2(x);\n")),
      "templates/test.saa:7: f: real2(...) needs 2 components but (real) give 1; list every component (HLSL does not splat one scalar)");
  EXPECT_EQ(load_error(function_template("real", "    return x > 0.0 ? x : 1;\n")),
            "templates/test.saa:7: f: the branches of '?:' are real and int; convert one explicitly so that both have one type");
  EXPECT_EQ(load_error(function_template("real", "    if (x) return x;\n    return 0.0;\n")),
            "templates/test.saa:7: f: the condition of 'if' is real, not bool; compare it (e.g. x > 0.0)");
}

TEST(DialectTypes, RefusesUnknownFunctionsAndWrongArguments) {
  EXPECT_EQ(load_error(function_template("real", "    return fast_sqrt(x);\n")),
            "templates/test.saa:7: f: unknown function 'fast_sqrt': neither a template function nor a dialect intrinsic "
            "(templates/intrinsics.sig); define it with @function or fix the name");
  EXPECT_EQ(load_error(function_template("real", "    return dot(x, real2(x, x));\n")),
            "templates/test.saa:7: f: no dot takes (real, real2); it takes (real, real) or (real2, real2) or (real3, real3) or "
            "(real4, real4); convert the arguments explicitly");
  const std::string helper = "@function h\nrole: helper\ncite: c\nreturns: real | r\nparam: real2 v | v\n{\n    return v.x;\n}\n";
  EXPECT_EQ(load_error(helper + function_template("real", "    return h(x);\n")),
            "templates/test.saa:15: f: h takes (real2) but is called with (real); convert the arguments explicitly");
  EXPECT_EQ(load_error(function_template("real", "    return y;\n")),
            "templates/test.saa:7: f: 'y' is not declared; declare it (TYPE y = ...) before its use, or name a parameter or a constant");
  EXPECT_EQ(load_error(function_template("real", "    return x.y;\n")), "templates/test.saa:7: f: '.y' needs a real vector, not real");
}

TEST(DialectTypes, RefusesWrongReturnTypesAndMissingReturns) {
  EXPECT_EQ(
      load_error(function_template("real", "    return real2(x, x);\n")),
      "templates/test.saa:7: f: returns real2 but the function is declared 'returns: real'; convert explicitly or fix the 'returns:' line");
  EXPECT_EQ(load_error(function_template("real", "    if (x > 0.0) return x;\n")),
            "templates/test.saa:7: f: the body can end without returning real; end every path with a return");
  EXPECT_EQ(load_error(function_template("real", "    return guarded(max(x, 1e-4), real2(x, x).x) + guarded(x, 1);\n")),
            "templates/test.saa:7: f: guarded(safe, paper) has a real safe form and a int paper form; both must have one type");
}

TEST(DialectTypes, RefusesSyntaxErrorsAtTheirLine) {
  EXPECT_EQ(load_error(function_template("real", "    real y = x * 2.0\n    return y;\n")),
            "templates/test.saa:8: f: expected ';' at the end of the statement, found 'return'");
  EXPECT_EQ(load_error(function_template("real", "    return guarded(x);\n")),
            "templates/test.saa:7: f: guarded(...) takes exactly two arguments: guarded(safe, paper)");
  EXPECT_EQ(
      load_error(function_template("real", "    float y = x;\n    return y;\n")),
      "templates/test.saa:7: f: 'float' is not a dialect type; declare locals as TYPE NAME = VALUE with real, real2, real3, real4, int or bool");
  EXPECT_EQ(
      load_error(function_template("real", "    return 1.0f;\n")),
      "templates/test.saa:7: f: '1.0f' is not a dialect number; write decimal numbers without suffixes (2.0, 1e-4, 3): the emitter adds "
      "precision suffixes");
}

// Every builtin template type-checks: each function keeps its typed tree, each return has the
// declared type, and a parameter the body assigns is recorded (WGSL parameters are immutable).
TEST(DialectTypes, TypesEveryBuiltinTemplate) {
  for (const Catalogue* catalogue : {&Catalogue::builtin(), &saagen::glints::catalogue()}) {
    ASSERT_FALSE(catalogue->functions().empty());
    for (const saagen::Function& function : catalogue->functions()) {
      ASSERT_NE(function.tree, nullptr) << function.name;
      for (const auto& stmt : function.tree->statements) {
        if (stmt->kind == dialect::StmtKind::return_value) {
          EXPECT_EQ(stmt->value->type.name(), function.return_type) << function.name;
        }
      }
    }
  }
  const saagen::Function* mix = saagen::glints::catalogue().find_function("glint_mix");
  ASSERT_NE(mix, nullptr);
  EXPECT_EQ(mix->tree->assigned_parameters, std::vector<std::string>{"v"});
}

// A C-like printer with the dialect's own spellings: printing gives back the template.
saagen::TargetSyntax dialect_spelling() {
  saagen::TargetSyntax target;
  for (const char* type : {"real", "real2", "real3", "real4", "int", "bool"}) target.types[type] = type;
  return target;
}

dialect::Body checked(const std::string& code, const std::string& returns = "real") {
  dialect::Body body = dialect::parse_body(code, {"templates/test.saa", 1, "f"});
  const std::map<std::string, dialect::FunctionSignature, std::less<>> functions;
  const std::map<std::string, dialect::Type, std::less<>> constants;
  dialect::FunctionSignature signature{*dialect::Type::from_name(returns),
                                       {{dialect::Type::real(), "a"},
                                        {dialect::Type::real(), "b"},
                                        {dialect::Type::real(), "c"},
                                        {dialect::Type::real(3), "v"},
                                        {dialect::Type::integer(), "n"}}};
  dialect::check_body(body, signature, {&functions, &constants, nullptr}, {"templates/test.saa", 1, "f"});
  return body;
}

std::string printed(const dialect::Body& body) { return dialect::print_c_like(body, dialect_spelling(), {}, true); }

TEST(DialectPrinter, RoundTripsLayoutCommentsAndStatements) {
  const std::string code =
      "    // a comment before a declaration\n"
      "    real s = a * (b + c);\n"
      "    int k = n;\n"
      "    for (int i = 0; i < 4; i += 1)\n"
      "    {\n"
      "        k = (k ^ i) & 65535;  // trailing comment\n"
      "    }\n"
      "    for (int i = 0; i < 2; ++i) k += i--;\n"
      "    if (s <= 0.0 || k == 0) return -s;\n"
      "    else if (!(s > 1.0)) return s;\n"
      "    return s + v.x\n"
      "             - v.y * real(k);\n";
  EXPECT_EQ(printed(checked(code)), code);
}

// The tree's structure as an S-expression, guards resolved to the safe form and the template's
// grouping parentheses left out.
std::string structure(const dialect::Expr& expr) {
  if (expr.kind == dialect::ExprKind::group) return structure(*expr.operands[0]);
  if (expr.kind == dialect::ExprKind::guarded) return structure(*expr.operands[0]);
  std::string text = "(" + std::to_string(static_cast<int>(expr.kind)) + " " + expr.text;
  for (const auto& operand : expr.operands) text += " " + structure(*operand);
  return text + ")";
}

std::string structure(const dialect::Stmt& stmt) {
  std::string text = "[" + std::to_string(static_cast<int>(stmt.kind)) + " " + stmt.type_name + " " + stmt.name;
  if (stmt.init) text += " " + structure(*stmt.init);
  if (stmt.value) text += " " + structure(*stmt.value);
  if (stmt.step) text += " " + structure(*stmt.step);
  for (const auto& inner : stmt.body) text += " " + structure(*inner);
  return text + "]";
}

std::string structure(const dialect::Body& body) {
  std::string text;
  for (const auto& stmt : body.statements) text += structure(*stmt);
  return text;
}

// Every builtin template, printed without its own parentheses (only those precedence needs),
// parses back to the same tree: the printer's precedence is C's.
TEST(DialectPrinter, EveryTemplatePrintedWithoutItsParenthesesParsesBackToTheSameTree) {
  for (const Catalogue* catalogue : {&Catalogue::builtin(), &saagen::glints::catalogue()}) {
    for (const saagen::Function& function : catalogue->functions()) {
      const dialect::SourcePlace place{function.source_file, function.body_line, function.name};
      dialect::Body bare = dialect::parse_body(function.body, place);
      dialect::drop_grouping(bare);
      const std::string printed_bare = dialect::print_c_like(bare, dialect_spelling(), {}, true);
      EXPECT_EQ(structure(dialect::parse_body(printed_bare, place)), structure(*function.tree)) << function.name << ":\n" << printed_bare;
    }
  }
}

TEST(DialectPrinter, KeepsTheParenthesesPrecedenceNeeds) {
  const auto without_grouping = [](const std::string& expression) {
    dialect::Body body = checked("    return " + expression + ";\n");
    dialect::drop_grouping(body);
    return printed(body);
  };
  EXPECT_EQ(without_grouping("a - (b - c)"), "    return a - (b - c);\n");
  EXPECT_EQ(without_grouping("(a * b) + c"), "    return a * b + c;\n");
  EXPECT_EQ(without_grouping("(a + b) * c"), "    return (a + b) * c;\n");
  EXPECT_EQ(without_grouping("(a - b) - c"), "    return a - b - c;\n");
  EXPECT_EQ(without_grouping("a / (b * c)"), "    return a / (b * c);\n");
  EXPECT_EQ(without_grouping("-(a + b)"), "    return -(a + b);\n");
  EXPECT_EQ(without_grouping("-(-a)"), "    return -(-a);\n");
  EXPECT_EQ(without_grouping("(a > b ? a : b) * c"), "    return (a > b ? a : b) * c;\n");
  EXPECT_EQ(without_grouping("(v * a).x"), "    return (v * a).x;\n");
  EXPECT_EQ(without_grouping("real((n & 3) + 1)"), "    return real((n & 3) + 1);\n");
  EXPECT_EQ(without_grouping("real(n & (3 + 1))"), "    return real(n & (3 + 1));\n");
  EXPECT_EQ(without_grouping("(a + b) < c ? a : b"), "    return a + b < c ? a : b;\n");
  EXPECT_EQ(without_grouping("real((n & 3) << 1)"), "    return real((n & 3) << 1);\n");
  EXPECT_EQ(without_grouping("(a < b) == (b < c) ? a : b"), "    return (a < b) == (b < c) ? a : b;\n");
}

TEST(DialectTree, CarriesTypesAndMutabilityForOtherPrinters) {
  const dialect::Body body = checked("    real s = a;\n    real t = b;\n    s = s * t;\n    return s + t * v.z;\n");
  ASSERT_EQ(body.statements.size(), 4u);
  EXPECT_TRUE(body.statements[0]->is_mutable);   // assigned later: WGSL `var`
  EXPECT_FALSE(body.statements[1]->is_mutable);  // never assigned: WGSL `let`
  const dialect::Expr& sum = *body.statements[3]->value;
  EXPECT_EQ(sum.type, dialect::Type::real());
  EXPECT_EQ(sum.operands[1]->operands[1]->type, dialect::Type::real());  // v.z
  EXPECT_EQ(sum.operands[1]->operands[1]->operands[0]->type, dialect::Type::real(3));
  const dialect::Body assigns_parameter = checked("    n = n + 1;\n    return real(n);\n");
  EXPECT_EQ(assigns_parameter.assigned_parameters, std::vector<std::string>{"n"});
}

TEST(DialectPrinter, SpellsTypesIntrinsicsAndNamesPerTarget) {
  const dialect::Body body = checked("    real3 w = saturate(lerp(v, v, real3(a, b, c)));\n    return rsqrt(dot(w, w)) * frac(a);\n");
  const saagen::NameMap names;
  EXPECT_EQ(dialect::print_c_like(body, saagen::builtin_target("glsl"), names, true),
            "    vec3 w = clamp(mix(v, v, vec3(a, b, c)), 0.0, 1.0);\n    return inversesqrt(dot(w, w)) * fract(a);\n");
  EXPECT_EQ(dialect::print_c_like(body, saagen::builtin_target("hlsl"), names, true),
            "    float3 w = saturate(lerp(v, v, float3(a, b, c)));\n    return rsqrt(dot(w, w)) * frac(a);\n");
}

TEST(DialectIntrinsics, TheTableIsDataWithGenericSignatures) {
  EXPECT_TRUE(dialect::is_intrinsic("saturate"));
  EXPECT_TRUE(dialect::is_derivative_intrinsic("ddx_fine"));
  EXPECT_FALSE(dialect::is_derivative_intrinsic("dot"));
  EXPECT_FALSE(dialect::is_intrinsic("mul"));
  const auto table = dialect::parse_intrinsics("# comment\nF twice(F)\nreal4 sample(real, real) resource dictionary\n", "x.sig");
  ASSERT_EQ(table.size(), 5u);  // F expands to real, real2, real3, real4
  EXPECT_EQ(table[3].result, dialect::Type::real(4));
  EXPECT_EQ(table[4].resource, "dictionary");
  try {
    dialect::parse_intrinsics("F broken(F\n", "x.sig");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "x.sig:1: expected a signature; write RESULT NAME(TYPE, ...) [derivative] [resource NAME]");
  }
}

}  // namespace
