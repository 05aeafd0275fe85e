// Aggregate shapes against their data type, and the value rules of docs/rapid-subset.md
// ("Validator rules") and docs/contracts.md ("The robot side"): normalised quaternions printed
// with enough decimals, v_tcp > 0, tool mass > 0.

#include <charconv>
#include <cmath>
#include <cstdio>

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/predefined.hpp"
#include "drivers/abb/rapid/types.hpp"
#include "drivers/abb/rapid/validate_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.8g", v);
    return buf;
}

// Whether the aggregate literal `e` has the shape of `type`; `problem` says where it does not.
bool fits(const Checker& c, const Expr& e, std::string_view type, std::string& problem) {
    const TypeInfo* t = find_type(type);
    if (t == nullptr) return true;
    const auto* agg = std::get_if<Aggregate>(&e.node);
    if (t->kind != TypeKind::record) {
        if (agg != nullptr) {
            problem = "an aggregate where " + std::string(t->name) + " is expected";
            return false;
        }
        const std::string actual = c.static_type(e);
        if (!compatible_types(t->name, actual)) {
            problem = std::string(t->name) + " expected, found " + actual;
            return false;
        }
        return true;
    }
    if (agg == nullptr) {
        const std::string actual = c.static_type(e);
        if (!compatible_types(t->name, actual)) {
            problem = std::string(t->name) + " expected, found " + actual;
            return false;
        }
        return true;
    }
    if (agg->items.size() != t->fields.size()) {
        problem = std::string(t->name) + " has " + std::to_string(t->fields.size()) +
                  " components, the aggregate " + std::to_string(agg->items.size());
        return false;
    }
    for (std::size_t i = 0; i < t->fields.size(); ++i) {
        std::string inner;
        if (!fits(c, agg->items[i], t->fields[i].type, inner)) {
            problem = "component " + std::to_string(i + 1) + " (" + std::string(t->fields[i].name) +
                      ") of " + std::string(t->name) + ": " + inner;
            return false;
        }
    }
    return true;
}

// Digits after the point, less the exponent: "0.707107" -> 6, "7.07107E-01" -> 6.
// Integer literals are exact only for 0 and ±1 (identity quaternions are written [1,0,0,0]).
bool enough_decimals(const Literal& l, std::size_t min) {
    const std::string& text = l.text;
    const auto e = text.find_first_of("eE");
    const auto dot = text.find('.');
    if (dot == std::string::npos && e == std::string::npos) {
        const double v = std::get<double>(l.value);
        return v == 0 || v == 1;
    }
    const std::string_view mantissa = std::string_view(text).substr(0, e);
    long long fraction = dot == std::string::npos || dot > mantissa.size()
                             ? 0
                             : static_cast<long long>(mantissa.size() - dot - 1);
    long long exponent = 0;
    if (e != std::string::npos) {
        std::string_view digits = std::string_view(text).substr(e + 1);
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        int parsed = 0;
        const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), parsed);
        if (r.ec == std::errc()) exponent = parsed;
    }
    return fraction - exponent >= static_cast<long long>(min);
}

}  // namespace

EvalContext Checker::constant_context() const {
    return EvalContext{[this](std::string_view name) -> const Value* {
                           const auto s = find_symbol(name);
                           if (!s || s->storage != Storage::constant) return nullptr;
                           if (s->decl != nullptr)
                               return s->decl->value ? &*s->decl->value : nullptr;
                           const PredefinedData* p = predefined_data(name);
                           return p != nullptr ? &p->value : nullptr;
                       },
                       {}};
}

Value Checker::evaluate_constant(const Expr& e) const {
    return evaluate(e, constant_context());
}

std::optional<Value> Checker::constant_value(const Expr& e) const {
    try {
        return evaluate_constant(e);
    } catch (const EvalError&) {
        return std::nullopt;
    }
}

bool Checker::check_typed(const Expr& e, std::string_view type, std::string_view what) {
    const TypeInfo* t = find_type(type);
    if (t == nullptr) {
        // "signal": any signal type; names from the I/O configuration have no known type.
        if (same_name(type, "signal")) {
            const std::string actual = static_type(e);
            if (!actual.empty() && !is_signal_type(actual)) {
                report(Rule::argument_type, e.line,
                       std::string(what) + " must be a signal, found " + actual);
                return false;
            }
        }
        return true;
    }
    if (std::holds_alternative<Aggregate>(e.node)) {
        std::string problem;
        if (!fits(*this, e, t->name, problem)) {
            report(Rule::aggregate_shape, e.line,
                   std::string(what) + " does not fit " + std::string(t->name) + ": " + problem);
            return false;
        }
        if (const auto v = constant_value(e))
            if (const auto typed = conform(*v, t->name))
                check_value(t->name, *typed, &e, e.line, what);
        return true;
    }
    const std::string actual = static_type(e);
    if (!compatible_types(t->name, actual)) {
        report(Rule::argument_type, e.line,
               std::string(what) + " must be " + std::string(t->name) + ", found " + actual);
        return false;
    }
    return true;
}

void Checker::check_value(std::string_view type, const Value& value, const Expr* e,
                          std::size_t line, std::string_view what) {
    if (value.is_items() && value.type.empty()) {  // an array: every element
        for (std::size_t i = 0; i < value.items().size(); ++i)
            check_value(type, value.items()[i], aggregate_item(e, {i}), line,
                        std::string(what) + "{" + std::to_string(i + 1) + "}");
        return;
    }
    if (!value.is_items()) return;
    const Value::Items& v = value.items();

    auto quaternion = [&](const Value& q, const Expr* qe, std::string_view part) {
        double n2 = 0;
        for (const Value& c : q.items()) n2 += c.num() * c.num();
        const double norm = std::sqrt(n2);
        const std::string where = std::string(part) + " of " + std::string(what);
        if (!std::isfinite(norm) || std::fabs(norm - 1) > options_.quaternion_tolerance)
            report(Rule::quaternion_norm, line,
                   where + " has norm " + number(norm) + "; it must be 1 within " +
                       number(options_.quaternion_tolerance));
        const auto* agg = qe != nullptr ? std::get_if<Aggregate>(&qe->node) : nullptr;
        if (agg == nullptr) return;
        for (std::size_t k = 0; k < agg->items.size(); ++k) {
            const Expr* c = &agg->items[k];
            while (const auto* u = std::get_if<Unary>(&c->node)) c = &*u->operand;
            const auto* lit = std::get_if<Literal>(&c->node);
            if (lit == nullptr || !std::holds_alternative<double>(lit->value)) continue;
            if (!enough_decimals(*lit, options_.min_quaternion_decimals)) {
                report(Rule::quaternion_digits, c->line,
                       "q" + std::to_string(k + 1) + " of the " + where + " is written '" +
                           lit->text + "'; write at least " +
                           std::to_string(options_.min_quaternion_decimals) + " decimals");
                return;  // once per quaternion
            }
        }
    };

    const std::string t = fold(type);
    if (t == "orient") {
        quaternion(value, e, "orientation");
    } else if (t == "pose") {
        quaternion(v[1], aggregate_item(e, {1}), "rotation");
    } else if (t == "robtarget") {
        quaternion(v[1], aggregate_item(e, {1}), "orientation");
    } else if (t == "loaddata") {
        quaternion(v[2], aggregate_item(e, {2}), "axes of moment");
    } else if (t == "wobjdata") {
        quaternion(v[3].items()[1], aggregate_item(e, {3, 1}), "user frame rotation");
        quaternion(v[4].items()[1], aggregate_item(e, {4, 1}), "object frame rotation");
    } else if (t == "tooldata") {
        quaternion(v[1].items()[1], aggregate_item(e, {1, 1}), "tool frame rotation");
        const Value::Items& load = v[2].items();
        quaternion(load[2], aggregate_item(e, {2, 2}), "load axes of moment");
        if (!(load[0].num() > 0))
            report(Rule::tool_mass, line,
                   "tool " + std::string(what) + " has load mass " + number(load[0].num()) +
                       " kg; it must be > 0");
        const Value::Items& cog = load[1].items();
        if (cog[0].num() == 0 && cog[1].num() == 0 && cog[2].num() == 0)
            report(Rule::tool_cog, line,
                   "tool " + std::string(what) +
                       " has its centre of gravity at the flange "
                       "origin [0,0,0]; give the real one",
                   Severity::warning);
    } else if (t == "speeddata") {
        if (!(v[0].num() > 0))
            report(Rule::speed, line,
                   "speed " + std::string(what) + " has v_tcp " + number(v[0].num()) +
                       " mm/s; it must be > 0");
    }
}

}  // namespace fibrecell::drivers::abb::rapid::detail
