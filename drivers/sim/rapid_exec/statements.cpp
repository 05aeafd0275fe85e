// Statements of the simulated RAPID task: assignment, IF, WHILE, FOR, TEST, calls (direct and
// late-bound), RETURN, EXIT, CONNECT. Each statement first passes a checkpoint (interrupts, stop).
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <type_traits>
#include <variant>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::RuntimeError;
using rapid_exec::Slot;
using rapid_exec::TaskError;
using rapid_exec::Variable;

// ---- Statements --------------------------------------------------------------------------------

RapidTask::Impl::Flow RapidTask::Impl::exec(const rapid::Block& block) {
    for (const rapid::Statement& s : block)
        if (exec(s)) return true;
    return false;
}

RapidTask::Impl::Flow RapidTask::Impl::exec(const rapid::Statement& s) {
    frame().line = s.line;
    {
        const std::lock_guard g(status_mu);
        shown.module = frame().module->name();
        shown.line = s.line;
    }
    checkpoint();
    try {
        return std::visit(
            [&](const auto& n) -> Flow {
                using T = std::decay_t<decltype(n)>;
                if constexpr (std::is_same_v<T, rapid::ProcCall>) {
                    call_proc(n.name, n.args, s.line);
                } else if constexpr (std::is_same_v<T, rapid::LateCall>) {
                    const std::string name = eval_string(n.routine);
                    auto [module, routine] = find_routine(name);
                    if (routine == nullptr || routine->kind != rapid::RoutineKind::proc)
                        throw RuntimeError(s.line, "late-bound call: no PROC '" + name +
                                                       "' in the task");
                    call_routine(module, *routine, n.args, s.line);
                } else if constexpr (std::is_same_v<T, rapid::Assign>) {
                    const Value v = eval(n.value);
                    rapid_exec::assign(resolve(n.target), v, s.line);
                } else if constexpr (std::is_same_v<T, rapid::If>) {
                    for (const rapid::IfBranch& b : n.branches) {
                        const Value c = eval(b.condition);
                        if (!c.is_bool()) throw RuntimeError(b.line, "IF condition is not a bool");
                        if (c.boolean()) return exec(b.body);
                    }
                    return exec(n.else_body);
                } else if constexpr (std::is_same_v<T, rapid::While>) {
                    for (;;) {
                        const Value c = eval(n.condition);
                        if (!c.is_bool()) throw RuntimeError(s.line, "WHILE condition is not a bool");
                        if (!c.boolean()) break;
                        if (exec(n.body)) return true;
                        frame().line = s.line;
                        checkpoint();  // an empty or fast loop still serves interrupts and stop
                    }
                } else if constexpr (std::is_same_v<T, rapid::For>) {
                    const double from = eval_num(n.from), to = eval_num(n.to);
                    const double step = n.step ? eval_num(*n.step) : (from <= to ? 1.0 : -1.0);
                    if (step == 0) throw RuntimeError(s.line, "FOR step is 0");
                    const std::string key = rapid::fold(n.variable);
                    Variable v{.name = n.variable, .type = "num", .read_only = true};
                    for (double i = from; step > 0 ? i <= to : i >= to; i += step) {
                        v.value = rapid::num_value(i);
                        frame().locals[key] = v;
                        if (exec(n.body)) {
                            frame().locals.erase(key);
                            return true;
                        }
                    }
                    frame().locals.erase(key);
                } else if constexpr (std::is_same_v<T, rapid::TestStatement>) {
                    const Value subject = eval(n.subject);
                    for (const rapid::TestCase& c : n.cases)
                        for (const Expr& e : c.values)
                            if (eval(e) == subject) return exec(c.body);
                    if (n.has_default) return exec(n.default_body);
                } else if constexpr (std::is_same_v<T, rapid::Return>) {
                    if (n.value) return_value = eval(*n.value);
                    return true;
                } else if constexpr (std::is_same_v<T, rapid::Exit>) {
                    throw rapid_exec::ExitSignal{};
                } else if constexpr (std::is_same_v<T, rapid::Connect>) {
                    const Slot target = resolve(n.interrupt);
                    if (!target.value->is_num())
                        throw RuntimeError(s.line, "CONNECT needs an intnum variable");
                    if (interrupts.find(rapid_exec::interrupt_number(*target.value)) != nullptr)
                        throw RuntimeError(s.line, "'" + target.what +
                                                       "' is already connected (ERR_ALRDYCNT)");
                    auto [module, trap] = find_routine(n.trap);
                    if (trap == nullptr || trap->kind != rapid::RoutineKind::trap)
                        throw RuntimeError(s.line, "no TRAP '" + n.trap + "'");
                    const std::int64_t number = interrupts.connect(module, *trap);
                    rapid_exec::assign(target, rapid::num_value(static_cast<double>(number)),
                                       s.line);
                }
                return false;
            },
            s.node);
    } catch (const rapid::EvalError& e) {
        throw TaskError(located(e.line() != 0 ? e.line() : s.line, e.what()));
    } catch (const RuntimeError& e) {
        throw TaskError(located(e.line() != 0 ? e.line() : s.line, e.what()));
    }
}

}  // namespace fibrecell::drivers::sim
