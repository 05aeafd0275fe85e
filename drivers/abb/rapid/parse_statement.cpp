// Statements: calls with optional arguments, assignments, late-bound calls, IF/WHILE/FOR/TEST,
// RETURN, EXIT, CONNECT.

#include "drivers/abb/rapid/parser_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

// Keywords that close or split a block; meeting one that the current block does not expect is a
// block error rather than a plain syntax error.
bool closes_something(const Token& t) {
    static constexpr std::string_view words[] = {
        "ENDMODULE", "ENDPROC", "ENDFUNC", "ENDTRAP", "ENDIF",   "ENDWHILE", "ENDFOR",
        "ENDTEST",   "ELSE",    "ELSEIF",  "CASE",    "DEFAULT", "MODULE",   "PROC",
        "FUNC",      "TRAP",    "ERROR",   "UNDO",    "BACKWARD"};
    for (std::string_view w : words)
        if (is_keyword(t, w)) return true;
    return false;
}

}  // namespace

Block Parser::statements(const OpenBlock& block,
                         std::initializer_list<std::string_view> terminators,
                         std::vector<DataDecl>& late_locals) {
    Block out;
    while (true) {
        const Token& t = peek();
        const std::string opened =
            std::string(block.keyword) + " opened on line " + std::to_string(block.line);
        if (t.kind == TokenKind::end)
            fail(Rule::block, block.line, opened + " is not closed by " + std::string(block.end));
        for (std::string_view term : terminators)
            if (is_keyword(t, term)) return out;
        if (is_keyword(t, "ERROR") || is_keyword(t, "UNDO") || is_keyword(t, "BACKWARD"))
            fail(Rule::syntax, t.line, "'" + t.text + "' handlers are not in the subset");
        if (closes_something(t))
            fail(Rule::block, t.line,
                 "'" + t.text + "' does not fit here: " + opened + " expects " +
                     std::string(block.end));
        if (at_declaration()) {
            report(Rule::declaration_order, t.line,
                   "data declared after the first statement of the routine; declarations come "
                   "first");
            late_locals.push_back(declaration(true));
            continue;
        }
        out.push_back(statement(late_locals));
    }
}

Statement Parser::statement(std::vector<DataDecl>& late_locals) {
    const Token& t = peek();
    const std::size_t line = t.line;
    DepthGuard guard(*this, line);
    if (is_keyword(t, "IF")) return if_statement(late_locals);
    if (is_keyword(t, "WHILE")) {
        take();
        While w{expression(), {}};
        expect_keyword("DO", "after the WHILE condition");
        w.body = statements({"WHILE", "ENDWHILE", line}, {"ENDWHILE"}, late_locals);
        take();
        return {std::move(w), line};
    }
    if (is_keyword(t, "FOR")) {
        take();
        std::string variable = declared_name("a loop variable");
        expect_keyword("FROM", "in FOR");
        Expr from = expression();
        expect_keyword("TO", "in FOR");
        Expr to = expression();
        For f{std::move(variable), std::move(from), std::move(to), std::nullopt, {}};
        if (at_keyword("STEP")) {
            take();
            f.step = expression();
        }
        expect_keyword("DO", "in FOR");
        f.body = statements({"FOR", "ENDFOR", line}, {"ENDFOR"}, late_locals);
        take();
        return {std::move(f), line};
    }
    if (is_keyword(t, "TEST")) {
        take();
        TestStatement test{expression(), {}, false, {}};
        const OpenBlock block{"TEST", "ENDTEST", line};
        while (at_keyword("CASE")) {
            TestCase c;
            c.line = take().line;
            while (true) {
                c.values.push_back(expression());
                if (!at_punct(",")) break;
                take();
            }
            expect_punct(":", "after the CASE values");
            c.body = statements(block, {"CASE", "DEFAULT", "ENDTEST"}, late_locals);
            test.cases.push_back(std::move(c));
        }
        if (at_keyword("DEFAULT")) {
            take();
            expect_punct(":", "after DEFAULT");
            test.has_default = true;
            test.default_body = statements(block, {"ENDTEST"}, late_locals);
        }
        expect_keyword("ENDTEST", "to close TEST on line " + std::to_string(line));
        return {std::move(test), line};
    }
    if (is_keyword(t, "RETURN")) {
        take();
        Return r;
        if (!at_punct(";")) r.value = expression();
        expect_punct(";", "after RETURN");
        return {std::move(r), line};
    }
    if (is_keyword(t, "EXIT")) {
        take();
        expect_punct(";", "after EXIT");
        return {Exit{}, line};
    }
    if (is_keyword(t, "CONNECT")) {
        take();
        Expr interrupt = postfix();
        expect_keyword("WITH", "in CONNECT");
        std::string trap = used_name("a trap routine name");
        expect_punct(";", "after CONNECT");
        return {Connect{std::move(interrupt), std::move(trap)}, line};
    }
    if (t.keyword && t.kind == TokenKind::identifier &&
        !(is_keyword(t, "NOT") || is_keyword(t, "TRUE") || is_keyword(t, "FALSE")))
        fail(Rule::syntax, line, "'" + t.text + "' is not a statement of the subset");
    return simple_statement();
}

// A call, an assignment or a late-bound call: the forms a one-line IF may hold.
Statement Parser::simple_statement() {
    const Token& t = peek();
    const std::size_t line = t.line;
    if (at_punct("%")) {
        take();
        Expr routine = expression();
        expect_punct("%", "to close the late-bound routine name");
        std::vector<Argument> args = call_arguments(";");
        expect_punct(";", "after the late-bound call");
        return {LateCall{std::move(routine), std::move(args)}, line};
    }
    if (t.kind != TokenKind::identifier || t.keyword) fail_unexpected("a statement");
    const Token& next = peek(1);
    if (is_punct(next, ":=") || is_punct(next, ".") || is_punct(next, "{")) {
        Expr target = postfix();
        expect_punct(":=", "in the assignment");
        Expr value = expression();
        expect_punct(";", "after the assignment");
        return {Assign{std::move(target), std::move(value)}, line};
    }
    std::string name = take().text;
    std::vector<Argument> args = call_arguments(";");
    expect_punct(";", "after the arguments of " + name);
    return {ProcCall{std::move(name), std::move(args)}, line};
}

Statement Parser::if_statement(std::vector<DataDecl>& late_locals) {
    const std::size_t line = take().line;
    If s;
    Expr condition = expression();
    if (!at_keyword("THEN")) {
        // The compact form: IF condition instruction;
        if (peek().kind != TokenKind::identifier && !at_punct("%")) fail_unexpected("THEN");
        Block body;
        body.push_back(simple_statement());
        s.branches.push_back({std::move(condition), std::move(body), line});
        return {std::move(s), line};
    }
    take();
    const OpenBlock block{"IF", "ENDIF", line};
    s.branches.push_back(
        {std::move(condition), statements(block, {"ELSEIF", "ELSE", "ENDIF"}, late_locals), line});
    while (at_keyword("ELSEIF")) {
        const std::size_t branch_line = take().line;
        Expr c = expression();
        expect_keyword("THEN", "after the ELSEIF condition");
        s.branches.push_back({std::move(c),
                              statements(block, {"ELSEIF", "ELSE", "ENDIF"}, late_locals),
                              branch_line});
    }
    if (at_keyword("ELSE")) {
        take();
        s.else_body = statements(block, {"ENDIF"}, late_locals);
    }
    expect_keyword("ENDIF", "to close IF on line " + std::to_string(line));
    return {std::move(s), line};
}

std::vector<Argument> Parser::call_arguments(std::string_view closing) {
    std::vector<Argument> args;
    if (at_punct(closing)) return args;
    bool first = true, after_comma = false;
    while (true) {
        const std::size_t line = peek().line;
        if (at_punct("\\")) {
            take();
            Argument a;
            a.line = line;
            a.name = used_name("an optional argument name");
            if (at_punct(":=")) {
                take();
                a.value = expression();
            }
            args.push_back(std::move(a));
        } else {
            if (!first && !after_comma)
                fail_unexpected("',' or '" + std::string(closing) + "' between arguments");
            Argument a;
            a.line = line;
            a.value = expression();
            args.push_back(std::move(a));
        }
        first = false;
        after_comma = false;
        if (at_punct(",")) {
            take();
            after_comma = true;
            continue;
        }
        if (at_punct(closing)) break;
        if (at_punct("\\")) continue;
        fail_unexpected("',' or '" + std::string(closing) + "' after an argument");
    }
    return args;
}

}  // namespace fibrecell::drivers::abb::rapid::detail
