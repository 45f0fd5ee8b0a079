// Parser of template function bodies into the typed syntax tree (saagen/front/syntax_tree.hpp):
// recursive descent over the dialect's tokens, C precedence, layout kept with each node.
#include "saagen/error.hpp"
#include "saagen/front/dialect.hpp"
#include "saagen/front/syntax_tree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace saagen::dialect {
namespace {

// A significant token with the whitespace and comments before it and its line.
struct Lexeme {
  std::string_view text;
  TokenKind kind;
  std::string_view leading;
  int line;
};

std::vector<Lexeme> lex(std::string_view code, int first_line, std::string_view& trailing) {
  std::vector<Lexeme> lexemes;
  int line = first_line;
  std::size_t layout_begin = 0, offset = 0;
  for (const Token& token : tokenize(code)) {
    if (token.kind != TokenKind::whitespace && token.kind != TokenKind::comment) {
      lexemes.push_back({token.text, token.kind, code.substr(layout_begin, offset - layout_begin), line});
      layout_begin = offset + token.text.size();
    }
    line += static_cast<int>(std::count(token.text.begin(), token.text.end(), '\n'));
    offset += token.text.size();
  }
  trailing = code.substr(layout_begin);
  return lexemes;
}

// Binary operators from the loosest to the tightest binding (C's table, without the comma).
constexpr std::array<std::array<std::string_view, 4>, 10> binary_levels = {{
    {"||"},
    {"&&"},
    {"|"},
    {"^"},
    {"&"},
    {"==", "!="},
    {"<", ">", "<=", ">="},
    {"<<", ">>"},
    {"+", "-"},
    {"*", "/", "%"},
}};

bool is_assignment_operator(std::string_view text) {
  static constexpr std::array<std::string_view, 11> operators = {"=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>="};
  return std::find(operators.begin(), operators.end(), text) != operators.end();
}

class Parser {
 public:
  Parser(std::string_view code, const SourcePlace& place) : place_(place) {
    std::string_view trailing;
    lexemes_ = lex(code, place.first_line, trailing);
    trailing_ = trailing;
    merge_compound_operators();
  }

  Body parse() {
    Body body;
    while (!at_end()) body.statements.push_back(statement());
    body.trailing = std::string(trailing_);
    return body;
  }

 private:
  // The tokenizer splits `+=`, `<<=`, `++`; operators are joined here when nothing separates them.
  void merge_compound_operators() {
    std::vector<Lexeme> merged;
    for (const Lexeme& lexeme : lexemes_) {
      if (!merged.empty() && lexeme.leading.empty() && lexeme.kind == TokenKind::punctuation &&
          merged.back().kind == TokenKind::punctuation) {
        const std::string joined = std::string(merged.back().text) + std::string(lexeme.text);
        if (is_assignment_operator(joined) || joined == "++" || joined == "--") {
          joined_.push_back(joined);
          merged.back().text = joined_.back();
          continue;
        }
      }
      merged.push_back(lexeme);
    }
    lexemes_ = std::move(merged);
  }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw Error(fmt::format("{}:{}: {}: {}", place_.file, line, place_.function, message));
  }

  bool at_end() const { return next_ >= lexemes_.size(); }
  const Lexeme& peek(std::size_t ahead = 0) const {
    static const Lexeme end{"", TokenKind::punctuation, "", 0};
    return next_ + ahead < lexemes_.size() ? lexemes_[next_ + ahead] : end;
  }
  int line() const { return at_end() ? (lexemes_.empty() ? place_.first_line : lexemes_.back().line) : peek().line; }
  bool next_is(std::string_view text) const { return !at_end() && peek().text == text; }
  const Lexeme& take() {
    if (at_end()) fail(line(), "the body ends in the middle of a statement; complete it");
    return lexemes_[next_++];
  }
  const Lexeme& expect(std::string_view text, std::string_view where) {
    if (!next_is(text)) {
      fail(line(),
           fmt::format("expected '{}' {}, found {}", text, where, at_end() ? "the end of the body" : "'" + std::string(peek().text) + "'"));
    }
    return take();
  }

  std::unique_ptr<Stmt> statement() {
    auto stmt = std::make_unique<Stmt>();
    stmt->leading = std::string(peek().leading);
    stmt->line = peek().line;
    const std::string_view word = peek().text;
    if (word == "{") return block(std::move(stmt));
    if (word == "if") return conditional(std::move(stmt));
    if (word == "for") return loop_for(std::move(stmt));
    if (word == "while") return loop_while(std::move(stmt));
    if (word == ";") {
      take();
      return stmt;
    }
    simple_statement(*stmt);
    expect(";", "at the end of the statement");
    return stmt;
  }

  // A declaration, a return, a jump or an expression, without its ';'.
  void simple_statement(Stmt& stmt) {
    const std::string_view word = peek().text;
    if (word == "return") {
      take();
      stmt.kind = StmtKind::return_value;
      if (!next_is(";")) stmt.value = expression();
    } else if (word == "break" || word == "continue") {
      stmt.kind = StmtKind::jump;
      stmt.jump_word = std::string(take().text);
    } else if (Type::from_name(word) && peek(1).kind == TokenKind::identifier) {
      stmt.kind = StmtKind::declaration;
      stmt.type_name = std::string(take().text);
      stmt.name = std::string(take().text);
      if (next_is("=")) {
        take();
        stmt.value = expression();
      }
    } else if (word == "const" || word == "float" || word == "vec2" || word == "vec3" || word == "float2" || word == "float3") {
      fail(
          line(),
          fmt::format("'{}' is not a dialect type; declare locals as TYPE NAME = VALUE with real, real2, real3, real4, int or bool", word));
    } else {
      stmt.kind = StmtKind::expression;
      stmt.value = expression();
    }
  }

  std::unique_ptr<Stmt> block(std::unique_ptr<Stmt> stmt) {
    stmt->kind = StmtKind::block;
    expect("{", "");
    while (!at_end() && !next_is("}")) stmt->body.push_back(statement());
    stmt->closing = std::string(peek().leading);
    expect("}", "to close the block");
    return stmt;
  }

  std::unique_ptr<Stmt> conditional(std::unique_ptr<Stmt> stmt) {
    stmt->kind = StmtKind::conditional;
    take();
    expect("(", "after 'if'");
    stmt->value = expression();
    expect(")", "after the condition");
    stmt->body.push_back(statement());
    if (next_is("else")) {
      stmt->closing = std::string(peek().leading);
      take();
      stmt->body.push_back(statement());
    }
    return stmt;
  }

  std::unique_ptr<Stmt> loop_for(std::unique_ptr<Stmt> stmt) {
    stmt->kind = StmtKind::loop_for;
    take();
    expect("(", "after 'for'");
    stmt->init = std::make_unique<Stmt>();
    stmt->init->line = line();
    if (!next_is(";")) simple_statement(*stmt->init);
    expect(";", "after the loop's initialiser");
    if (!next_is(";")) stmt->value = expression();
    expect(";", "after the loop's condition");
    if (!next_is(")")) stmt->step = expression();
    expect(")", "after the loop's step");
    stmt->body.push_back(statement());
    return stmt;
  }

  std::unique_ptr<Stmt> loop_while(std::unique_ptr<Stmt> stmt) {
    stmt->kind = StmtKind::loop_while;
    take();
    expect("(", "after 'while'");
    stmt->value = expression();
    expect(")", "after the condition");
    stmt->body.push_back(statement());
    return stmt;
  }

  std::unique_ptr<Expr> node(ExprKind kind, const Lexeme& first, std::string text = {}) const {
    auto expr = std::make_unique<Expr>();
    expr->kind = kind;
    expr->text = std::move(text);
    expr->leading = std::string(first.leading);
    expr->line = first.line;
    return expr;
  }

  std::unique_ptr<Expr> expression() { return assignment(); }

  std::unique_ptr<Expr> assignment() {
    auto target = ternary();
    if (at_end() || !is_assignment_operator(peek().text)) return target;
    const Lexeme& op = take();
    auto expr = std::make_unique<Expr>();
    expr->kind = ExprKind::assign;
    expr->text = std::string(op.text);
    expr->line = op.line;
    expr->leading = std::move(target->leading);
    target->leading.clear();
    expr->separators.push_back(std::string(op.leading));
    expr->operands.push_back(std::move(target));
    expr->operands.push_back(assignment());
    return expr;
  }

  std::unique_ptr<Expr> ternary() {
    auto condition = binary(0);
    if (!next_is("?")) return condition;
    auto expr = std::make_unique<Expr>();
    expr->kind = ExprKind::ternary;
    expr->line = condition->line;
    expr->leading = std::move(condition->leading);
    condition->leading.clear();
    expr->separators.push_back(std::string(take().leading));
    expr->operands.push_back(std::move(condition));
    expr->operands.push_back(assignment());
    expr->separators.push_back(std::string(expect(":", "in the conditional expression c ? a : b").leading));
    expr->operands.push_back(assignment());
    return expr;
  }

  // The binding level of a binary operator (index into binary_levels), or -1.
  int binary_level(const Lexeme& lexeme) const {
    if (lexeme.kind != TokenKind::punctuation) return -1;
    for (std::size_t level = 0; level < binary_levels.size(); ++level) {
      for (std::string_view op : binary_levels[level]) {
        if (!op.empty() && op == lexeme.text) return static_cast<int>(level);
      }
    }
    return -1;
  }

  // Precedence climbing: operators of level >= min_level, left-associative.
  std::unique_ptr<Expr> binary(int min_level) {
    auto left = unary();
    for (int level = at_end() ? -1 : binary_level(peek()); level >= min_level; level = at_end() ? -1 : binary_level(peek())) {
      const Lexeme& op = take();
      auto expr = std::make_unique<Expr>();
      expr->kind = ExprKind::binary;
      expr->text = std::string(op.text);
      expr->line = op.line;
      expr->leading = std::move(left->leading);
      left->leading.clear();
      expr->separators.push_back(std::string(op.leading));
      expr->operands.push_back(std::move(left));
      expr->operands.push_back(binary(level + 1));
      left = std::move(expr);
    }
    return left;
  }

  std::unique_ptr<Expr> unary() {
    if (!at_end() && (peek().text == "-" || peek().text == "!" || peek().text == "~" || peek().text == "+")) {
      const Lexeme& op = take();
      auto expr = node(ExprKind::unary, op, std::string(op.text));
      expr->operands.push_back(unary());
      return expr;
    }
    if (next_is("++") || next_is("--")) {
      const Lexeme& op = take();
      auto expr = node(ExprKind::unary, op, std::string(op.text));
      expr->operands.push_back(unary());
      return expr;
    }
    return postfix(primary());
  }

  std::unique_ptr<Expr> postfix(std::unique_ptr<Expr> expr) {
    for (;;) {
      if (next_is(".")) {
        take();
        if (peek().kind != TokenKind::identifier) fail(line(), "expected a swizzle (x, y, z, w) after '.'");
        auto member = std::make_unique<Expr>();
        member->kind = ExprKind::member;
        member->text = std::string(take().text);
        member->line = expr->line;
        member->leading = std::move(expr->leading);
        expr->leading.clear();
        member->operands.push_back(std::move(expr));
        expr = std::move(member);
      } else if (next_is("[")) {
        take();
        auto index = std::make_unique<Expr>();
        index->kind = ExprKind::index;
        index->line = expr->line;
        index->leading = std::move(expr->leading);
        expr->leading.clear();
        index->operands.push_back(std::move(expr));
        index->operands.push_back(expression());
        index->separators.push_back(std::string(expect("]", "to close the index").leading));
        expr = std::move(index);
      } else if (next_is("++") || next_is("--")) {
        auto step = std::make_unique<Expr>();
        step->kind = ExprKind::postfix;
        step->text = std::string(take().text);
        step->line = expr->line;
        step->leading = std::move(expr->leading);
        expr->leading.clear();
        step->operands.push_back(std::move(expr));
        expr = std::move(step);
      } else {
        return expr;
      }
    }
  }

  std::unique_ptr<Expr> primary() {
    if (at_end()) fail(line(), "the body ends in the middle of an expression; complete it");
    const Lexeme& first = take();
    if (first.kind == TokenKind::number) return node(ExprKind::literal, first, std::string(first.text));
    if (first.text == "(") {
      auto group = node(ExprKind::group, first);
      group->operands.push_back(expression());
      group->separators.push_back(std::string(expect(")", "to close the parenthesis").leading));
      return group;
    }
    if (first.kind != TokenKind::identifier) fail(first.line, fmt::format("unexpected '{}' where a value is expected", first.text));
    if (first.text == "true" || first.text == "false") return node(ExprKind::literal, first, std::string(first.text));
    if (!next_is("(")) return node(ExprKind::name, first, std::string(first.text));
    auto call = node(first.text == "guarded" ? ExprKind::guarded : ExprKind::call, first, std::string(first.text));
    take();
    if (!next_is(")")) {
      call->operands.push_back(expression());
      while (next_is(",")) {
        take();
        call->operands.push_back(expression());
      }
    }
    call->separators.push_back(std::string(expect(")", fmt::format("to close the call of {}", first.text)).leading));
    if (call->kind == ExprKind::guarded && call->operands.size() != 2) {
      fail(first.line, "guarded(...) takes exactly two arguments: guarded(safe, paper)");
    }
    return call;
  }

  SourcePlace place_;
  std::vector<Lexeme> lexemes_;
  std::string_view trailing_;
  std::size_t next_ = 0;
  // Storage of merged operator texts; a deque-like list keeps their addresses stable.
  struct Joined {
    std::vector<std::unique_ptr<std::string>> texts;
    void push_back(const std::string& text) { texts.push_back(std::make_unique<std::string>(text)); }
    const std::string& back() const { return *texts.back(); }
  } joined_;
};

}  // namespace

Body parse_body(std::string_view code, const SourcePlace& place) { return Parser(code, place).parse(); }

}  // namespace saagen::dialect
