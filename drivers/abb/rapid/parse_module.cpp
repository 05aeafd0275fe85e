// The module level of the grammar: MODULE, data declarations, routine headers; and the cursor.

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/parser_detail.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace detail {
namespace {

bool is_end_keyword(const Token& t) {
    static constexpr std::string_view ends[] = {
        "ENDMODULE", "ENDPROC",   "ENDFUNC", "ENDTRAP", "ENDIF", "ENDWHILE", "ENDFOR",
        "ENDTEST",   "ENDRECORD", "ELSE",    "ELSEIF",  "CASE",  "DEFAULT"};
    for (std::string_view e : ends)
        if (is_keyword(t, e)) return true;
    return false;
}

}  // namespace

// ---- cursor ----

const Token& Parser::peek(std::size_t ahead) const {
    const std::size_t i = pos_ + ahead;
    return i < tokens_.size() ? tokens_[i] : tokens_.back();
}

const Token& Parser::take() {
    const Token& t = peek();
    if (pos_ + 1 < tokens_.size()) ++pos_;
    return t;
}

void Parser::report(Rule rule, std::size_t line, std::string message) {
    diagnostics_.push_back({options_.file_name, line, rule, std::move(message)});
}

void Parser::fail(Rule rule, std::size_t line, std::string message) {
    report(rule, line, std::move(message));
    throw StopParsing{};
}

std::string Parser::describe(const Token& t) const {
    switch (t.kind) {
        case TokenKind::end:
            return "end of file";
        case TokenKind::string:
            return "string \"" + t.text + "\"";
        default:
            return "'" + t.text + "'";
    }
}

void Parser::fail_unexpected(std::string_view expected) {
    const Token& t = peek();
    if (t.kind == TokenKind::invalid) throw StopParsing{};  // the lexer has reported it
    fail(Rule::syntax, t.line, "expected " + std::string(expected) + ", found " + describe(t));
}

void Parser::expect_keyword(std::string_view word, std::string_view context) {
    if (!at_keyword(word)) fail_unexpected(std::string(word) + " " + std::string(context));
    take();
}

void Parser::expect_punct(std::string_view p, std::string_view context) {
    if (!at_punct(p)) fail_unexpected("'" + std::string(p) + "' " + std::string(context));
    take();
}

std::string Parser::declared_name(std::string_view what) {
    const Token& t = peek();
    if (t.kind != TokenKind::identifier) fail_unexpected(what);
    if (t.keyword) {
        // Keep going: the rest of the declaration may hold more problems worth reporting.
        if (is_end_keyword(t) || is_keyword(t, "MODULE") || is_keyword(t, "PROC"))
            fail_unexpected(what);
        report(Rule::reserved_word, t.line,
               "reserved word '" + t.text + "' cannot be used as " + std::string(what));
    }
    return take().text;
}

std::string Parser::used_name(std::string_view what) {
    const Token& t = peek();
    if (t.kind != TokenKind::identifier || t.keyword) fail_unexpected(what);
    return take().text;
}

Parser::DepthGuard::DepthGuard(Parser& parser, std::size_t line) : p(parser) {
    if (++p.depth_ > p.options_.max_nesting) {
        p.report(Rule::nesting_depth, line,
                 "nested deeper than " + std::to_string(p.options_.max_nesting) + " levels");
        --p.depth_;
        throw StopParsing{};
    }
}

// ---- module ----

Module Parser::module() {
    if (at_end()) fail(Rule::module_count, 0, "file holds no MODULE");
    if (!at_keyword("MODULE")) fail_unexpected("MODULE");
    Module m;
    m.line = take().line;
    m.name = declared_name("module name");
    if (at_punct("(")) {
        take();
        while (true) {
            if (peek().kind != TokenKind::identifier) fail_unexpected("a module attribute");
            m.attributes.push_back(take().text);
            if (!at_punct(",")) break;
            take();
        }
        expect_punct(")", "after the module attributes");
    }
    while (true) {
        const Token& t = peek();
        if (t.kind == TokenKind::end)
            fail(Rule::block, m.line,
                 "MODULE " + m.name + " opened on line " + std::to_string(m.line) +
                     " is not closed by ENDMODULE");
        if (at_keyword("ENDMODULE")) {
            m.end_line = take().line;
            break;
        }
        if (at_declaration()) {
            m.data.push_back(declaration(false));
            continue;
        }
        const bool local = at_keyword("LOCAL");
        const Token& head = peek(local ? 1 : 0);
        if (is_keyword(head, "PROC") || is_keyword(head, "FUNC") || is_keyword(head, "TRAP")) {
            m.routines.push_back(routine());
            continue;
        }
        if (is_end_keyword(t))
            fail(Rule::block, t.line,
                 "'" + t.text + "' inside MODULE " + m.name + " (opened on line " +
                     std::to_string(m.line) + "); expected ENDMODULE");
        if (is_keyword(t, "RECORD") || is_keyword(t, "ALIAS"))
            fail(Rule::syntax, t.line, "'" + t.text + "' declarations are not in the subset");
        fail_unexpected("a data declaration, a routine or ENDMODULE");
    }
    if (!at_end()) {
        if (at_keyword("MODULE"))
            fail(Rule::module_count, peek().line, "second MODULE in the file; one module per file");
        fail_unexpected("end of file after ENDMODULE");
    }
    return m;
}

bool Parser::at_declaration() const {
    const std::size_t i = (at_keyword("LOCAL") || at_keyword("TASK")) ? 1 : 0;
    const Token& t = peek(i);
    return is_keyword(t, "VAR") || is_keyword(t, "PERS") || is_keyword(t, "CONST");
}

DataDecl Parser::declaration(bool in_routine) {
    DataDecl d;
    d.line = peek().line;
    if (at_keyword("LOCAL") || at_keyword("TASK")) {
        const Token& v = take();
        d.visibility = is_keyword(v, "LOCAL") ? Visibility::local : Visibility::task;
        if (in_routine)
            report(Rule::declaration, v.line,
                   "'" + v.text + "' applies to module data, not to routine data");
    }
    const Token& storage = take();
    d.storage = is_keyword(storage, "VAR")    ? Storage::var
                : is_keyword(storage, "PERS") ? Storage::pers
                                              : Storage::constant;
    if (d.visibility == Visibility::task && d.storage != Storage::pers)
        report(Rule::declaration, d.line, "TASK applies to PERS data only");
    d.type = used_name("a data type");
    d.name = declared_name("a data name");
    if (at_punct("{")) {
        take();
        while (true) {
            d.dims.push_back(expression());
            if (!at_punct(",")) break;
            take();
        }
        expect_punct("}", "after the array dimensions");
    }
    if (at_punct(":=")) {
        take();
        d.init = expression();
    }
    expect_punct(";", "after the declaration of " + d.name);
    return d;
}

Routine Parser::routine() {
    Routine r;
    r.line = peek().line;
    if (at_keyword("LOCAL")) {
        take();
        r.local = true;
    }
    const Token& kind = take();
    std::string_view opener = "PROC", closer = "ENDPROC";
    if (is_keyword(kind, "FUNC")) {
        r.kind = RoutineKind::func;
        opener = "FUNC";
        closer = "ENDFUNC";
        r.return_type = used_name("the FUNC's return type");
    } else if (is_keyword(kind, "TRAP")) {
        r.kind = RoutineKind::trap;
        opener = "TRAP";
        closer = "ENDTRAP";
    }
    r.name = declared_name("a routine name");
    if (r.kind != RoutineKind::trap) {
        expect_punct("(", "after the routine name " + r.name);
        while (!at_punct(")")) {
            if (!r.params.empty()) expect_punct(",", "between parameters");
            Param p;
            p.line = peek().line;
            if (at_punct("\\")) {
                take();
                p.optional = true;
            }
            if (at_keyword("VAR"))
                p.access = ParamAccess::var;
            else if (at_keyword("PERS"))
                p.access = ParamAccess::pers;
            else if (at_keyword("INOUT"))
                p.access = ParamAccess::inout;
            if (p.access != ParamAccess::in) take();
            p.type = used_name("a parameter type");
            p.name = declared_name("a parameter name");
            if (at_punct("{")) {
                take();
                while (true) {
                    expect_punct("*", "in an array parameter");
                    ++p.array_dims;
                    if (!at_punct(",")) break;
                    take();
                }
                expect_punct("}", "after an array parameter");
            }
            if (at_punct("|"))
                fail(Rule::syntax, peek().line,
                     "alternative parameters ('|') are not in the subset");
            r.params.push_back(std::move(p));
        }
        take();  // ')'
    }
    while (at_declaration()) r.locals.push_back(declaration(true));
    const OpenBlock block{opener, closer, r.line};
    r.body = statements(block, {closer}, r.locals);
    r.end_line = take().line;
    return r;
}

}  // namespace detail

ParseResult parse_module(std::string_view text, const ParseOptions& options) {
    LexResult lexed = lex(text, options.file_name);
    ParseResult result;
    result.diagnostics = std::move(lexed.diagnostics);
    detail::Parser parser(lexed.tokens, options, result.diagnostics);
    try {
        Module m = parser.module();
        m.header = std::move(lexed.header);
        m.file = options.file_name;
        m.line_count = lexed.line_count;
        detail::evaluate_declarations(m);
        result.module = std::move(m);
    } catch (const detail::StopParsing&) {
    }
    return result;
}

}  // namespace fibrecell::drivers::abb::rapid
