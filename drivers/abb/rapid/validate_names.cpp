// Scopes and name resolution: FOR variables, parameters, routine data, module data, predefined
// data, configured signals and external data, in that order. Declared before use means: module
// data initialisers see only earlier module data, routine data initialisers only earlier routine
// data; statements see everything of their routine and module.

#include "drivers/abb/rapid/instructions.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/predefined.hpp"
#include "drivers/abb/rapid/types.hpp"
#include "drivers/abb/rapid/validate_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

Symbol from_decl(const DataDecl& d, Symbol::Origin origin) {
    Symbol s;
    s.origin = origin;
    s.type = d.type;
    s.storage = d.storage;
    s.is_array = !d.dims.empty();
    s.decl = &d;
    return s;
}

}  // namespace

std::optional<Symbol> Checker::find_symbol(std::string_view name) const {
    for (auto it = loop_variables_.rbegin(); it != loop_variables_.rend(); ++it)
        if (same_name(*it, name)) return Symbol{Symbol::Origin::loop_variable, "num"};
    if (routine_ != nullptr) {
        for (const Param& p : routine_->params) {
            if (!same_name(p.name, name)) continue;
            Symbol s;
            s.origin = Symbol::Origin::param;
            s.type = p.type;
            s.storage = p.access == ParamAccess::pers ? Storage::pers : Storage::var;
            s.is_array = p.array_dims > 0;
            s.in_param = p.access == ParamAccess::in;
            return s;
        }
        for (std::size_t i = 0; i < visible_locals_ && i < routine_->locals.size(); ++i)
            if (same_name(routine_->locals[i].name, name))
                return from_decl(routine_->locals[i], Symbol::Origin::local);
    }
    for (std::size_t i = 0; i < visible_module_data_ && i < module_.data.size(); ++i)
        if (same_name(module_.data[i].name, name))
            return from_decl(module_.data[i], Symbol::Origin::module_data);
    if (const auto p = predefined_data(name)) {
        Symbol s;
        s.origin = Symbol::Origin::predefined;
        s.type = std::string(p->type);
        s.storage = p->constant ? Storage::constant : Storage::pers;
        return s;
    }
    for (const std::string& sig : options_.known_signals)
        if (same_name(sig, name)) return Symbol{Symbol::Origin::signal, ""};
    for (const ExternalData& d : options_.external_data)
        if (same_name(d.name, name)) return Symbol{Symbol::Origin::external, d.type, Storage::pers};
    return std::nullopt;
}

std::string Checker::undeclared_reason(std::string_view name) const {
    const std::string quoted = "'" + std::string(name) + "'";
    if (routine_ != nullptr)
        for (const DataDecl& d : routine_->locals)
            if (same_name(d.name, name))
                return quoted + " is used before its declaration on line " + std::to_string(d.line);
    for (const DataDecl& d : module_.data)
        if (same_name(d.name, name))
            return quoted + " is used before its declaration on line " + std::to_string(d.line);
    if (module_.find_routine(name) != nullptr) return quoted + " is a routine, not data";
    return quoted + " is not declared";
}

bool Checker::is_callable_function(std::string_view name) const {
    if (is_builtin_function(name)) return true;
    const Routine* r = module_.find_routine(name);
    if (r != nullptr) return r->kind == RoutineKind::func;
    return is_external_routine(name);
}

bool Checker::is_external_routine(std::string_view name, std::string_view module) const {
    for (const std::string& entry : options_.external_routines) {
        const std::string_view e(entry);
        const auto colon = e.find(':');
        const std::string_view proc = colon == std::string_view::npos ? e : e.substr(colon + 1);
        const std::string_view mod = colon == std::string_view::npos ? "" : e.substr(0, colon);
        if (same_name(proc, name) && (module.empty() || mod.empty() || same_name(mod, module)))
            return true;
    }
    return false;
}

std::string_view Checker::function_type(std::string_view name) const {
    const Routine* r = module_.find_routine(name);
    if (r != nullptr && r->kind == RoutineKind::func) return r->return_type;
    return builtin_function_type(name);
}

void Checker::check_declared_name(std::string_view name, std::size_t line, std::string_view what) {
    const std::string quoted = "'" + std::string(name) + "'";
    std::string clash;
    if (is_predefined_data(name))
        clash = "predefined data";
    else if (is_builtin_instruction(name))
        clash = "a built-in instruction";
    else if (is_builtin_function(name))
        clash = "a built-in function";
    else if (find_type(name) != nullptr)
        clash = "a data type";
    if (!clash.empty())
        report(Rule::builtin_name, line,
               quoted + " (" + std::string(what) + ") redeclares " + clash);
}

void Checker::check_names(const Expr& e) {
    std::visit(
        [&](const auto& n) {
            using T = std::decay_t<decltype(n)>;
            if constexpr (std::is_same_v<T, NameRef>) {
                if (!find_symbol(n.name))
                    report(Rule::undeclared, e.line, undeclared_reason(n.name));
            } else if constexpr (std::is_same_v<T, Aggregate>) {
                for (const Expr& i : n.items) check_names(i);
            } else if constexpr (std::is_same_v<T, ComponentAccess>) {
                check_names(*n.base);
                const std::string base = static_type(*n.base);
                const TypeInfo* t = base.empty() ? nullptr : find_type(base);
                if (t != nullptr && !field_index(base, n.component))
                    report(Rule::undeclared, e.line,
                           std::string(t->name) + " has no component '" + n.component + "'");
            } else if constexpr (std::is_same_v<T, IndexAccess>) {
                check_names(*n.base);
                for (const Expr& i : n.indices) check_names(i);
            } else if constexpr (std::is_same_v<T, Unary>) {
                check_names(*n.operand);
            } else if constexpr (std::is_same_v<T, Binary>) {
                check_names(*n.lhs);
                check_names(*n.rhs);
            } else if constexpr (std::is_same_v<T, FunctionCall>) {
                if (!is_callable_function(n.name))
                    report(Rule::undeclared, e.line, "unknown function '" + n.name + "'");
                for (const Argument& a : n.args)
                    if (a.value) check_names(*a.value);
            }
        },
        e.node);
}

std::string Checker::static_type(const Expr& e) const {
    return std::visit(
        [&](const auto& n) -> std::string {
            using T = std::decay_t<decltype(n)>;
            if constexpr (std::is_same_v<T, Literal>) {
                return std::holds_alternative<double>(n.value) ? "num"
                       : std::holds_alternative<bool>(n.value) ? "bool"
                                                               : "string";
            } else if constexpr (std::is_same_v<T, NameRef>) {
                const auto s = find_symbol(n.name);
                return s && !s->is_array ? s->type : std::string();
            } else if constexpr (std::is_same_v<T, ComponentAccess>) {
                return std::string(field_type(static_type(*n.base), n.component));
            } else if constexpr (std::is_same_v<T, IndexAccess>) {
                const auto* name = std::get_if<NameRef>(&n.base->node);
                const auto s = name ? find_symbol(name->name) : std::nullopt;
                return s && s->is_array ? s->type : std::string();
            } else if constexpr (std::is_same_v<T, Unary>) {
                return n.op == UnaryOp::logical_not ? "bool" : static_type(*n.operand);
            } else if constexpr (std::is_same_v<T, Binary>) {
                switch (n.op) {
                    case BinaryOp::eq:
                    case BinaryOp::ne:
                    case BinaryOp::lt:
                    case BinaryOp::gt:
                    case BinaryOp::le:
                    case BinaryOp::ge:
                    case BinaryOp::logical_and:
                    case BinaryOp::logical_or:
                    case BinaryOp::logical_xor:
                        return "bool";
                    default:
                        break;
                }
                const std::string a = static_type(*n.lhs), b = static_type(*n.rhs);
                if (is_num_type(a) && is_num_type(b)) return "num";
                if (a == "string" && b == "string" && n.op == BinaryOp::add) return "string";
                return {};
            } else if constexpr (std::is_same_v<T, FunctionCall>) {
                return std::string(function_type(n.name));
            } else {
                return {};
            }
        },
        e.node);
}

}  // namespace fibrecell::drivers::abb::rapid::detail
