// Expressions, lowest precedence first: OR XOR < AND < NOT < relations < + - < * / DIV MOD <
// unary - + < postfix (.component, {index}) < primary.

#include "drivers/abb/rapid/parser_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

Expr make_binary(BinaryOp op, Expr lhs, Expr rhs) {
    const std::size_t line = lhs.line;
    return {Binary{op, std::move(lhs), std::move(rhs)}, line};
}

}  // namespace

Expr Parser::expression() {
    DepthGuard guard(*this, peek().line);
    return or_expr();
}

Expr Parser::or_expr() {
    Expr lhs = and_expr();
    while (at_keyword("OR") || at_keyword("XOR")) {
        const BinaryOp op = at_keyword("OR") ? BinaryOp::logical_or : BinaryOp::logical_xor;
        take();
        lhs = make_binary(op, std::move(lhs), and_expr());
    }
    return lhs;
}

Expr Parser::and_expr() {
    Expr lhs = not_expr();
    while (at_keyword("AND")) {
        take();
        lhs = make_binary(BinaryOp::logical_and, std::move(lhs), not_expr());
    }
    return lhs;
}

Expr Parser::not_expr() {
    if (!at_keyword("NOT")) return relation();
    const std::size_t line = take().line;
    DepthGuard guard(*this, line);
    return {Unary{UnaryOp::logical_not, not_expr()}, line};
}

Expr Parser::relation() {
    Expr lhs = sum();
    static constexpr std::pair<std::string_view, BinaryOp> ops[] = {
        {"=", BinaryOp::eq}, {"<>", BinaryOp::ne}, {"<", BinaryOp::lt},
        {">", BinaryOp::gt}, {"<=", BinaryOp::le}, {">=", BinaryOp::ge}};
    for (const auto& [text, op] : ops) {
        if (at_punct(text)) {
            take();
            return make_binary(op, std::move(lhs), sum());
        }
    }
    return lhs;
}

Expr Parser::sum() {
    Expr lhs = product();
    while (at_punct("+") || at_punct("-")) {
        const BinaryOp op = at_punct("+") ? BinaryOp::add : BinaryOp::sub;
        take();
        lhs = make_binary(op, std::move(lhs), product());
    }
    return lhs;
}

Expr Parser::product() {
    Expr lhs = unary();
    while (true) {
        BinaryOp op;
        if (at_punct("*"))
            op = BinaryOp::mul;
        else if (at_punct("/"))
            op = BinaryOp::div;
        else if (at_keyword("DIV"))
            op = BinaryOp::int_div;
        else if (at_keyword("MOD"))
            op = BinaryOp::mod;
        else
            return lhs;
        take();
        lhs = make_binary(op, std::move(lhs), unary());
    }
}

Expr Parser::unary() {
    if (!at_punct("-") && !at_punct("+")) return postfix();
    const UnaryOp op = at_punct("-") ? UnaryOp::minus : UnaryOp::plus;
    const std::size_t line = take().line;
    DepthGuard guard(*this, line);
    return {Unary{op, unary()}, line};
}

Expr Parser::postfix() {
    Expr base = primary();
    while (true) {
        const std::size_t line = peek().line;
        if (at_punct(".")) {
            take();
            std::string component = used_name("a component name");
            base = {ComponentAccess{std::move(base), std::move(component)}, line};
        } else if (at_punct("{")) {
            take();
            std::vector<Expr> indices;
            while (true) {
                indices.push_back(expression());
                if (!at_punct(",")) break;
                take();
            }
            expect_punct("}", "after the array index");
            base = {IndexAccess{std::move(base), std::move(indices)}, line};
        } else {
            return base;
        }
    }
}

Expr Parser::primary() {
    const Token& t = peek();
    const std::size_t line = t.line;
    if (t.kind == TokenKind::number) {
        take();
        return {Literal{t.number, t.text}, line};
    }
    if (t.kind == TokenKind::string) {
        take();
        return {Literal{t.text, {}}, line};
    }
    if (is_keyword(t, "TRUE") || is_keyword(t, "FALSE")) {
        take();
        return {Literal{is_keyword(t, "TRUE"), t.text}, line};
    }
    if (at_punct("[")) {
        take();
        Aggregate a;
        a.items.reserve(6);  // robtarget rows: 3, 4, 4, 6 items
        while (true) {
            a.items.push_back(expression());
            if (!at_punct(",")) break;
            take();
        }
        expect_punct("]", "to close the aggregate");
        return {std::move(a), line};
    }
    if (at_punct("(")) {
        take();
        Expr e = expression();
        expect_punct(")", "to close the parenthesis");
        return e;
    }
    if (t.kind == TokenKind::identifier && !t.keyword) {
        std::string name = take().text;
        if (at_punct("(")) {
            take();
            std::vector<Argument> args = call_arguments(")");
            expect_punct(")", "after the arguments of " + name);
            return {FunctionCall{std::move(name), std::move(args)}, line};
        }
        return {NameRef{std::move(name)}, line};
    }
    fail_unexpected("an expression");
}

}  // namespace fibrecell::drivers::abb::rapid::detail
