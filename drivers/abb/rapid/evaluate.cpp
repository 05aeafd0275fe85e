#include "drivers/abb/rapid/evaluate.hpp"

#include <cmath>
#include <type_traits>
#include <variant>

#include "drivers/abb/rapid/builtin_functions.hpp"
#include "drivers/abb/rapid/names.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

std::string kind_of(const Value& v) {
    if (v.is_num()) return "num";
    if (v.is_bool()) return "bool";
    if (v.is_string()) return "string";
    if (v.is_items()) return v.type.empty() ? std::string("aggregate") : v.type;
    return v.type.empty() ? std::string("no value") : v.type;
}

// A pos given as a typed pos or as an untyped [x, y, z] aggregate.
bool is_pos(const Value& v) {
    if (!v.is_items() || v.items().size() != 3 || !(v.type.empty() || v.type == "pos"))
        return false;
    for (const Value& i : v.items())
        if (!i.is_num()) return false;
    return true;
}

Value pos_from(double x, double y, double z) {
    return items_value({num_value(x), num_value(y), num_value(z)}, "pos");
}

// Exact integer for DIV and MOD (num holds integers exactly only up to 2^23 on the controller;
// doubles here, so up to 2^53).
double integer_operand(const Value& v, std::size_t line, std::string_view op) {
    if (!v.is_num() || !std::isfinite(v.num()) || v.num() != std::trunc(v.num()) ||
        std::fabs(v.num()) > 9007199254740992.0)
        throw EvalError(line, std::string(op) + " needs integer operands, found " + kind_of(v));
    return v.num();
}

Value binary(BinaryOp op, const Value& a, const Value& b, std::size_t line) {
    auto mismatch = [&]() -> EvalError {
        return EvalError(line, "operator " + std::string(to_string(op)) + " cannot combine " +
                                   kind_of(a) + " and " + kind_of(b));
    };
    switch (op) {
        case BinaryOp::logical_and:
        case BinaryOp::logical_or:
        case BinaryOp::logical_xor: {
            if (!a.is_bool() || !b.is_bool()) throw mismatch();
            const bool x = a.boolean(), y = b.boolean();
            return bool_value(op == BinaryOp::logical_and  ? (x && y)
                              : op == BinaryOp::logical_or ? (x || y)
                                                           : (x != y));
        }
        case BinaryOp::eq:
        case BinaryOp::ne: {
            if (a.data.index() != b.data.index()) throw mismatch();
            return bool_value((a == b) == (op == BinaryOp::eq));
        }
        case BinaryOp::lt:
        case BinaryOp::gt:
        case BinaryOp::le:
        case BinaryOp::ge: {
            if (!a.is_num() || !b.is_num()) throw mismatch();
            const double x = a.num(), y = b.num();
            return bool_value(op == BinaryOp::lt   ? x < y
                              : op == BinaryOp::gt ? x > y
                              : op == BinaryOp::le ? x <= y
                                                   : x >= y);
        }
        case BinaryOp::add:
            if (a.is_num() && b.is_num()) return num_value(a.num() + b.num());
            if (a.is_string() && b.is_string()) {
                std::string s = a.string() + b.string();
                if (s.size() > max_string_length)
                    throw EvalError(
                        line, "string of " + std::to_string(s.size()) + " characters; at most 80");
                return string_value(std::move(s));
            }
            if (is_pos(a) && is_pos(b))
                return pos_from(a.items()[0].num() + b.items()[0].num(),
                                a.items()[1].num() + b.items()[1].num(),
                                a.items()[2].num() + b.items()[2].num());
            throw mismatch();
        case BinaryOp::sub:
            if (a.is_num() && b.is_num()) return num_value(a.num() - b.num());
            if (is_pos(a) && is_pos(b))
                return pos_from(a.items()[0].num() - b.items()[0].num(),
                                a.items()[1].num() - b.items()[1].num(),
                                a.items()[2].num() - b.items()[2].num());
            throw mismatch();
        case BinaryOp::mul:
            if (a.is_num() && b.is_num()) return num_value(a.num() * b.num());
            if (a.is_num() && is_pos(b))
                return pos_from(a.num() * b.items()[0].num(), a.num() * b.items()[1].num(),
                                a.num() * b.items()[2].num());
            if (is_pos(a) && b.is_num())
                return pos_from(b.num() * a.items()[0].num(), b.num() * a.items()[1].num(),
                                b.num() * a.items()[2].num());
            throw mismatch();
        case BinaryOp::div:
            if (!b.is_num() || !(a.is_num() || is_pos(a))) throw mismatch();
            if (b.num() == 0) throw EvalError(line, "division by zero");
            if (a.is_num()) return num_value(a.num() / b.num());
            return pos_from(a.items()[0].num() / b.num(), a.items()[1].num() / b.num(),
                            a.items()[2].num() / b.num());
        case BinaryOp::int_div:
        case BinaryOp::mod: {
            const double x = integer_operand(a, line, to_string(op));
            const double y = integer_operand(b, line, to_string(op));
            if (y == 0) throw EvalError(line, "division by zero");
            return num_value(op == BinaryOp::int_div ? std::trunc(x / y) : std::fmod(x, y));
        }
    }
    throw mismatch();
}

class Evaluator {
  public:
    explicit Evaluator(const EvalContext& context) : context_(context) {}

    Value operator()(const Expr& e) const {
        return std::visit([&](const auto& node) { return eval(node, e.line); }, e.node);
    }

  private:
    Value eval(const Literal& l, std::size_t) const {
        return std::visit(
            [](const auto& v) -> Value {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, double>)
                    return num_value(v);
                else if constexpr (std::is_same_v<T, bool>)
                    return bool_value(v);
                else
                    return string_value(v);
            },
            l.value);
    }

    Value eval(const NameRef& n, std::size_t line) const {
        const Value* v = context_.lookup ? context_.lookup(n.name) : nullptr;
        if (v == nullptr) throw EvalError(line, "'" + n.name + "' has no value here");
        return *v;
    }

    Value eval(const Aggregate& a, std::size_t) const {
        Value::Items items;
        items.reserve(a.items.size());
        for (const Expr& i : a.items) items.push_back((*this)(i));
        return items_value(std::move(items));
    }

    Value eval(const ComponentAccess& c, std::size_t line) const {
        const Value base = (*this)(*c.base);
        const Value* v = component(base, c.component);
        if (v == nullptr)
            throw EvalError(line, kind_of(base) + " has no component '" + c.component + "'");
        return *v;
    }

    Value eval(const IndexAccess& ix, std::size_t line) const {
        Value current = (*this)(*ix.base);
        for (const Expr& e : ix.indices) {
            const Value i = (*this)(e);
            if (!current.is_items() || !current.type.empty())
                throw EvalError(line, "indexing " + kind_of(current) + ", which is not an array");
            const auto& items = current.items();
            if (!i.is_num() || i.num() != std::trunc(i.num()) || i.num() < 1 ||
                i.num() > static_cast<double>(items.size()))
                throw EvalError(line, "index " + to_rapid_text(i) + " outside 1.." +
                                          std::to_string(items.size()));
            Value next = items[static_cast<std::size_t>(i.num()) - 1];
            current = std::move(next);
        }
        return current;
    }

    Value eval(const Unary& u, std::size_t line) const {
        const Value v = (*this)(*u.operand);
        if (u.op == UnaryOp::logical_not) {
            if (!v.is_bool()) throw EvalError(line, "NOT needs a bool, found " + kind_of(v));
            return bool_value(!v.boolean());
        }
        if (v.is_num()) return num_value(u.op == UnaryOp::minus ? -v.num() : v.num());
        if (is_pos(v) && u.op == UnaryOp::minus)
            return pos_from(-v.items()[0].num(), -v.items()[1].num(), -v.items()[2].num());
        throw EvalError(
            line, "unary " + std::string(to_string(u.op)) + " needs a num, found " + kind_of(v));
    }

    Value eval(const Binary& b, std::size_t line) const {
        const Value lhs = (*this)(*b.lhs);
        const Value rhs = (*this)(*b.rhs);
        return binary(b.op, lhs, rhs, line);
    }

    Value eval(const FunctionCall& f, std::size_t line) const {
        if (context_.call) {
            if (auto v = context_.call(f, line)) return std::move(*v);
        }
        if (!is_pure_builtin(f.name))
            throw EvalError(line, "function '" + f.name + "' cannot be evaluated here");
        BuiltinArgs args;
        for (const Argument& a : f.args) {
            if (a.positional())
                args.positional.push_back((*this)(*a.value));
            else
                args.optional.push_back(
                    {a.name, a.value ? std::optional<Value>((*this)(*a.value)) : std::nullopt});
        }
        return call_builtin(f.name, args, line);
    }

    const EvalContext& context_;
};

}  // namespace

Value evaluate(const Expr& expr, const EvalContext& context) {
    return Evaluator(context)(expr);
}

std::vector<std::size_t> evaluate_extents(const std::vector<Expr>& dims,
                                          const EvalContext& context) {
    std::vector<std::size_t> extents;
    double total = 1;
    for (const Expr& d : dims) {
        const Value v = evaluate(d, context);
        if (!v.is_num() || v.num() != std::trunc(v.num()) || v.num() < 1)
            throw EvalError(
                d.line, "array dimension must be a positive integer, found " + to_rapid_text(v));
        total *= v.num();
        if (total > static_cast<double>(max_array_elements))
            throw EvalError(
                d.line, "array of more than " + std::to_string(max_array_elements) + " elements");
        extents.push_back(static_cast<std::size_t>(v.num()));
    }
    return extents;
}

}  // namespace fibrecell::drivers::abb::rapid
