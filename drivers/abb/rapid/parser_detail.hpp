#pragma once
// Internal to the parser: the recursive-descent parser shared by parse_module.cpp,
// parse_statement.cpp and parse_expression.cpp.

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/diagnostic.hpp"
#include "drivers/abb/rapid/lexer.hpp"
#include "drivers/abb/rapid/parser.hpp"
#include "drivers/abb/rapid/program.hpp"

namespace fibrecell::drivers::abb::rapid::detail {

// Thrown to unwind after the diagnostic that stops parsing has been recorded.
struct StopParsing {};

// An open block, for "IF opened on line 3 is closed by ENDWHILE" messages.
struct OpenBlock {
    std::string_view keyword;  // "IF"
    std::string_view end;      // "ENDIF"
    std::size_t line = 0;
};

class Parser {
  public:
    Parser(const std::vector<Token>& tokens, const ParseOptions& options,
           std::vector<Diagnostic>& diagnostics)
        : tokens_(tokens), options_(options), diagnostics_(diagnostics) {}

    Module module();  // throws StopParsing

    // ---- cursor (parse_module.cpp) ----
    const Token& peek(std::size_t ahead = 0) const;
    const Token& take();
    bool at_keyword(std::string_view word) const { return is_keyword(peek(), word); }
    bool at_punct(std::string_view p) const { return is_punct(peek(), p); }
    bool at_end() const { return peek().kind == TokenKind::end; }
    void expect_keyword(std::string_view word, std::string_view context);
    void expect_punct(std::string_view p, std::string_view context);
    // A name being declared: reserved words are reported (reserved-word) and accepted.
    std::string declared_name(std::string_view what);
    // A name being used (type, instruction, component): reserved words stop the parser.
    std::string used_name(std::string_view what);
    void report(Rule rule, std::size_t line, std::string message);
    [[noreturn]] void fail(Rule rule, std::size_t line, std::string message);
    [[noreturn]] void fail_unexpected(std::string_view expected);
    std::string describe(const Token& t) const;

    // ---- declarations and routines (parse_module.cpp) ----
    bool at_declaration() const;
    DataDecl declaration(bool in_routine);
    Routine routine();

    // ---- statements (parse_statement.cpp) ----
    // Statements until one of `terminators` (keywords, upper case); misplaced declarations go to
    // `late_locals` with a declaration-order report.
    Block statements(const OpenBlock& block, std::initializer_list<std::string_view> terminators,
                     std::vector<DataDecl>& late_locals);
    Statement statement(std::vector<DataDecl>& late_locals);
    std::vector<Argument> call_arguments(std::string_view closing);

    // ---- expressions (parse_expression.cpp) ----
    Expr expression();
    Expr postfix();

  private:
    Expr or_expr();
    Expr and_expr();
    Expr not_expr();
    Expr relation();
    Expr sum();
    Expr product();
    Expr unary();
    Expr primary();
    Statement if_statement(std::vector<DataDecl>& late_locals);
    Statement simple_statement();

    struct DepthGuard {
        Parser& p;
        DepthGuard(Parser& parser, std::size_t line);
        ~DepthGuard() { --p.depth_; }
        DepthGuard(const DepthGuard&) = delete;
        DepthGuard& operator=(const DepthGuard&) = delete;
    };

    const std::vector<Token>& tokens_;
    const ParseOptions& options_;
    std::vector<Diagnostic>& diagnostics_;
    std::size_t pos_ = 0;
    std::size_t depth_ = 0;
};

// Fills DataDecl::extents and ::value where the reader can evaluate them (parse_values.cpp).
void evaluate_declarations(Module& module);

}  // namespace fibrecell::drivers::abb::rapid::detail
