// Statements: calls against the instruction table or the called routine's parameters,
// assignments, late-bound calls, conditions, FOR variables, RETURN, CONNECT.

#include "drivers/abb/rapid/instructions.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/validate_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

std::size_t positional_count(const std::vector<Argument>& args) {
    std::size_t n = 0;
    for (const Argument& a : args) n += a.positional() ? 1 : 0;
    return n;
}

// The data name an assignment writes: x, x.trans.z, x{3}.
const NameRef* assigned_name(const Expr& target) {
    const Expr* e = &target;
    while (true) {
        if (const auto* c = std::get_if<ComponentAccess>(&e->node))
            e = &*c->base;
        else if (const auto* i = std::get_if<IndexAccess>(&e->node))
            e = &*i->base;
        else
            return std::get_if<NameRef>(&e->node);
    }
}

std::string known_optionals(const InstructionInfo& info) {
    std::string out;
    for (const OptionalParam& o : info.optionals)
        out += (out.empty() ? "\\" : ", \\") + std::string(o.name);
    return out.empty() ? "none" : out;
}

}  // namespace

void Checker::check_block(const Block& block) {
    for (const Statement& s : block) check_statement(s);
}

void Checker::check_statement(const Statement& s) {
    std::visit(
        [&](const auto& n) {
            using T = std::decay_t<decltype(n)>;
            if constexpr (std::is_same_v<T, ProcCall>) {
                check_call(n, s.line);
            } else if constexpr (std::is_same_v<T, LateCall>) {
                check_late_call(n, s.line);
            } else if constexpr (std::is_same_v<T, Assign>) {
                check_assign(n, s.line);
            } else if constexpr (std::is_same_v<T, If>) {
                for (const IfBranch& b : n.branches) {
                    check_names(b.condition);
                    check_typed(b.condition, "bool", "the IF condition");
                    check_block(b.body);
                }
                check_block(n.else_body);
            } else if constexpr (std::is_same_v<T, While>) {
                check_names(n.condition);
                check_typed(n.condition, "bool", "the WHILE condition");
                check_block(n.body);
            } else if constexpr (std::is_same_v<T, For>) {
                check_declared_name(n.variable, s.line, "a loop variable");
                for (const Expr* e : {&n.from, &n.to, n.step ? &*n.step : nullptr}) {
                    if (e == nullptr) continue;
                    check_names(*e);
                    check_typed(*e, "num", "a FOR bound");
                }
                loop_variables_.push_back(n.variable);
                check_block(n.body);
                loop_variables_.pop_back();
            } else if constexpr (std::is_same_v<T, TestStatement>) {
                check_names(n.subject);
                for (const TestCase& c : n.cases) {
                    for (const Expr& v : c.values) check_names(v);
                    check_block(c.body);
                }
                check_block(n.default_body);
            } else if constexpr (std::is_same_v<T, Return>) {
                const bool in_func = routine_ != nullptr && routine_->kind == RoutineKind::func;
                if (in_func && !n.value)
                    report(Rule::syntax, s.line,
                           "RETURN in FUNC " + routine_->name + " needs a value");
                if (!in_func && n.value)
                    report(Rule::syntax, s.line, "RETURN with a value outside a FUNC");
                if (n.value) {
                    check_names(*n.value);
                    if (in_func) check_typed(*n.value, routine_->return_type, "the returned value");
                }
            } else if constexpr (std::is_same_v<T, Connect>) {
                check_names(n.interrupt);
                check_typed(n.interrupt, "intnum", "the CONNECT interrupt");
                const Routine* trap = module_.find_routine(n.trap);
                if (trap == nullptr || trap->kind != RoutineKind::trap)
                    report(Rule::undeclared, s.line,
                           "no TRAP routine '" + n.trap + "' in the module");
            }
        },
        s.node);
}

void Checker::check_call(const ProcCall& call, std::size_t line) {
    for (const Argument& a : call.args)
        if (a.value) check_names(*a.value);

    if (const InstructionInfo* info = find_instruction(call.name)) {
        const std::string name(info->name);
        const std::size_t given = positional_count(call.args);
        if (given != info->params.size())
            report(Rule::argument_count, line,
                   name + " takes " + std::to_string(info->params.size()) +
                       " positional arguments, found " + std::to_string(given));
        std::vector<std::string> seen;
        for (const Argument& a : call.args) {
            if (a.positional()) continue;
            const OptionalParam* op = nullptr;
            for (const OptionalParam& o : info->optionals)
                if (same_name(o.name, a.name)) op = &o;
            bool repeated = false;
            for (const std::string& s : seen) repeated = repeated || same_name(s, a.name);
            seen.push_back(a.name);
            if (op == nullptr)
                report(Rule::optional_argument, a.line,
                       name + " has no optional argument \\" + a.name + " (it has " +
                           known_optionals(*info) + ")");
            else if (repeated)
                report(Rule::optional_argument, a.line, name + ": \\" + a.name + " given twice");
            else if (op->type.empty() && a.value)
                report(Rule::optional_argument, a.line,
                       name + ": \\" + std::string(op->name) + " is a switch and takes no value");
            else if (!op->type.empty() && !a.value)
                report(Rule::optional_argument, a.line,
                       name + ": \\" + std::string(op->name) + " needs a value (\\" +
                           std::string(op->name) + ":=...)");
            else if (a.value)
                check_typed(*a.value, op->type, name + " \\" + std::string(op->name));
        }
        for (std::size_t i = 0; i < info->params.size(); ++i)
            if (const Expr* e = positional(call.args, i))
                check_typed(*e, info->params[i], name + " argument " + std::to_string(i + 1));
        return;
    }

    if (const Routine* r = module_.find_routine(call.name)) {
        if (r->kind != RoutineKind::proc) {
            report(Rule::undeclared, line,
                   "'" + r->name + "' is a " + std::string(to_string(r->kind)) +
                       "; only a PROC can be called as an instruction");
            return;
        }
        std::vector<const Param*> required;
        for (const Param& p : r->params)
            if (!p.optional) required.push_back(&p);
        const std::size_t given = positional_count(call.args);
        if (given != required.size())
            report(Rule::argument_count, line,
                   r->name + " takes " + std::to_string(required.size()) +
                       " positional arguments, found " + std::to_string(given));
        for (std::size_t i = 0; i < required.size(); ++i)
            if (const Expr* e = positional(call.args, i))
                check_typed(*e, required[i]->type, r->name + " argument " + std::to_string(i + 1));
        for (const Argument& a : call.args) {
            if (a.positional()) continue;
            bool known = false;
            for (const Param& p : r->params)
                known = known || (p.optional && same_name(p.name, a.name));
            if (!known)
                report(Rule::optional_argument, a.line,
                       r->name + " has no optional parameter \\" + a.name);
        }
        return;
    }
    if (is_external_routine(call.name)) return;
    if (find_symbol(call.name))
        report(Rule::undeclared, line,
               "'" + call.name + "' is data, not an instruction or procedure");
    else
        report(Rule::undeclared, line, "unknown instruction or procedure '" + call.name + "'");
}

void Checker::check_late_call(const LateCall& call, std::size_t line) {
    check_names(call.routine);
    check_typed(call.routine, "string", "the late-bound routine name");
    for (const Argument& a : call.args)
        if (a.value) check_names(*a.value);
    const auto* lit = std::get_if<Literal>(&call.routine.node);
    if (lit == nullptr || !std::holds_alternative<std::string>(lit->value)) return;
    // Only a literal can be checked here; a computed name is the simulator's business.
    const std::string& text = std::get<std::string>(lit->value);
    const auto colon = text.find(':');
    const std::string mod = colon == std::string::npos ? "" : text.substr(0, colon);
    const std::string proc = colon == std::string::npos ? text : text.substr(colon + 1);
    if (!is_identifier(proc) || (colon != std::string::npos && !is_identifier(mod))) {
        report(Rule::late_call, line,
               "late-bound call to \"" + text + "\": expected \"Proc\" or \"Module:Proc\"");
        return;
    }
    if (mod.empty() || same_name(mod, module_.name)) {
        const Routine* r = module_.find_routine(proc);
        if (r != nullptr && r->kind == RoutineKind::proc) return;
    }
    if (is_external_routine(proc, mod)) return;
    report(Rule::late_call, line,
           "late-bound call to \"" + text +
               "\": no such PROC in this module or in the known external routines");
}

void Checker::check_assign(const Assign& a, std::size_t line) {
    check_names(a.target);
    check_names(a.value);
    const NameRef* name = assigned_name(a.target);
    if (name == nullptr) {
        report(Rule::const_assignment, line, "the left side of ':=' is not data");
        return;
    }
    const auto s = find_symbol(name->name);
    if (!s) return;  // reported as undeclared
    if (s->origin == Symbol::Origin::loop_variable) {
        report(Rule::const_assignment, line,
               "FOR loop variable '" + name->name + "' cannot be assigned");
        return;
    }
    if (s->storage == Storage::constant) {
        report(Rule::const_assignment, line,
               "'" + name->name + "' is CONST and cannot be assigned");
        return;
    }
    const std::string type = static_type(a.target);
    if (!type.empty()) check_typed(a.value, type, "the value assigned to " + name->name);
}

}  // namespace fibrecell::drivers::abb::rapid::detail
