// Routine calls (argument binding, routine data), name and routine lookup, and expressions of the
// simulated RAPID task.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/instructions.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/predefined.hpp"
#include "drivers/abb/rapid/types.hpp"

#include <algorithm>
#include <type_traits>
#include <variant>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::Frame;
using rapid_exec::LoadedModule;
using rapid_exec::RuntimeError;
using rapid_exec::Slot;
using rapid_exec::TaskError;
using rapid_exec::Variable;

namespace {

std::string canonical_type(const std::string& type) {
    const rapid::TypeInfo* t = rapid::find_type(type);
    return t != nullptr ? std::string(t->name) : type;
}

// Pops the frame pushed for a call, also when the call unwinds.
struct FramePop {
    std::vector<std::unique_ptr<Frame>>& frames;
    ~FramePop() { frames.pop_back(); }
};

}  // namespace

std::string RapidTask::Impl::located(std::size_t line, const std::string& message) {
    const std::string module = frames.empty() ? std::string("?") : frame().module->name();
    return module + " line " + std::to_string(line) + ": " + message;
}

// ---- Names -------------------------------------------------------------------------------------

std::optional<Slot> RapidTask::Impl::find_slot(const std::string& name) {
    const std::string key = rapid::fold(name);
    if (!frames.empty()) {
        Frame& f = frame();
        if (auto it = f.refs.find(key); it != f.refs.end()) return it->second;
        if (auto it = f.locals.find(key); it != f.locals.end())
            return rapid_exec::slot_of(it->second);
        if (auto it = f.module->data.find(key); it != f.module->data.end())
            return rapid_exec::slot_of(it->second);
    }
    for (auto& m : modules) {
        auto it = m->data.find(key);
        if (it != m->data.end() && !it->second.local) return rapid_exec::slot_of(it->second);
    }
    if (auto it = predefined.find(key); it != predefined.end())
        return rapid_exec::slot_of(it->second);
    if (const rapid::PredefinedData* p = rapid::predefined_data(name)) {
        Variable v{.name = name,
                   .type = std::string(p->type),
                   .storage = p->constant ? rapid::Storage::constant : rapid::Storage::pers,
                   .read_only = true,
                   .value = p->value,
                   .initial = p->value};
        return rapid_exec::slot_of(predefined[key] = std::move(v));
    }
    return std::nullopt;
}

std::pair<std::shared_ptr<LoadedModule>, const rapid::Routine*> RapidTask::Impl::find_routine(
    const std::string& name) {
    // "Module:Routine" (late binding) names the module.
    if (const auto colon = name.find(':'); colon != std::string::npos) {
        const std::string module = name.substr(0, colon), routine = name.substr(colon + 1);
        for (auto& m : modules)
            if (rapid::same_name(m->name(), module))
                if (const rapid::Routine* r = m->module->find_routine(routine)) return {m, r};
        return {nullptr, nullptr};
    }
    if (!frames.empty())
        if (const rapid::Routine* r = frame().module->module->find_routine(name))
            return {frame().module, r};
    for (auto& m : modules)
        if (const rapid::Routine* r = m->module->find_routine(name); r != nullptr && !r->local)
            return {m, r};
    return {nullptr, nullptr};
}

Slot RapidTask::Impl::resolve(const Expr& target) {
    return std::visit(
        [&](const auto& n) -> Slot {
            using T = std::decay_t<decltype(n)>;
            if constexpr (std::is_same_v<T, rapid::NameRef>) {
                auto s = find_slot(n.name);
                if (!s) throw RuntimeError(target.line, "'" + n.name + "' is not data");
                return *s;
            } else if constexpr (std::is_same_v<T, rapid::ComponentAccess>) {
                return rapid_exec::component_slot(resolve(*n.base), n.component, target.line);
            } else if constexpr (std::is_same_v<T, rapid::IndexAccess>) {
                Slot s = resolve(*n.base);
                for (const Expr& i : n.indices)
                    s = rapid_exec::element_slot(s, eval(i), target.line);
                return s;
            } else {
                throw RuntimeError(target.line, "not data that can be written");
            }
        },
        target.node);
}

// ---- Expressions -------------------------------------------------------------------------------

RapidTask::Impl::Value RapidTask::Impl::eval(const Expr& e) {
    const rapid::EvalContext context{
        .lookup = [this](std::string_view name) -> const Value* {
            if (auto s = find_slot(std::string(name))) return s->value;
            // A signal used as a value reads it (diFcPause = 1).
            try {
                if (io.read_signal) {
                    signal_scratch = rapid::num_value(io.read_signal(std::string(name)));
                    return &signal_scratch;
                }
            } catch (const std::out_of_range&) {
            }
            return nullptr;
        },
        .call = [this](const rapid::FunctionCall& f, std::size_t line) {
            return call_function(f, line);
        }};
    return rapid::evaluate(e, context);
}

std::optional<RapidTask::Impl::Value> RapidTask::Impl::call_function(const rapid::FunctionCall& f,
                                                                     std::size_t line) {
    const std::string name = rapid::fold(f.name);
    const auto args = rapid::positional_args(f.args);
    auto one_arg = [&]() -> const Expr& {
        if (args.size() != 1) throw RuntimeError(line, f.name + " takes one argument");
        return *args[0];
    };
    if (name == "dinput" || name == "ginput" || name == "doutput" || name == "goutput" ||
        name == "ainput" || name == "aoutput")
        return rapid::num_value(read_signal(signal_name(one_arg()), line));
    if (name == "crobt") return current_robtarget(f, line);
    if (name == "isfile") return rapid::bool_value(read_file(eval_string(one_arg()), line).has_value());
    if (name == "present") {
        const Expr& a = one_arg();
        const auto* n = std::get_if<rapid::NameRef>(&a.node);
        if (n == nullptr || frames.empty())
            throw RuntimeError(line, "Present needs a parameter name");
        const auto& absent = frame().absent;
        return rapid::bool_value(std::find(absent.begin(), absent.end(), rapid::fold(n->name)) ==
                                 absent.end());
    }
    auto [module, routine] = find_routine(f.name);
    if (routine == nullptr) return std::nullopt;  // a pure built-in, or an error in evaluate()
    if (routine->kind != rapid::RoutineKind::func)
        throw RuntimeError(line, "'" + f.name + "' is not a FUNC");
    auto v = call_routine(module, *routine, f.args, line);
    if (!v) throw RuntimeError(line, "FUNC " + routine->name + " ended without RETURN");
    return v;
}

// CRobT(\Tool \WObj): where the robot is now, as a robtarget of the tool in the work object
// (tool0 and wobj0 when not given). Exact once the robot stands still, as after a stop point.
RapidTask::Impl::Value RapidTask::Impl::current_robtarget(const rapid::FunctionCall& f,
                                                          std::size_t line) {
    if (!rapid::positional_args(f.args).empty())
        throw RuntimeError(line, "CRobT takes only \\Tool and \\WObj");
    for (const rapid::Argument& a : f.args)
        if (!rapid::same_name(a.name, "Tool") && !rapid::same_name(a.name, "WObj"))
            throw RuntimeError(line, "CRobT: \\" + a.name + " is not executed");
    auto data = [&](const char* arg, const char* fallback) {
        const rapid::Argument* a = rapid::find_optional(f.args, arg);
        return a != nullptr && a->value ? eval(*a->value) : *find_slot(fallback)->value;
    };
    const auto tool = rapid::to_tooldata(data("Tool", "tool0"));
    const auto wobj = rapid::to_wobjdata(data("WObj", "wobj0"));
    if (!tool) throw RuntimeError(line, "CRobT: \\Tool is not a tooldata");
    if (!wobj) throw RuntimeError(line, "CRobT: \\WObj is not a wobjdata");
    return rapid::to_value(motion.robtarget(*tool, *wobj));
}

// ---- Calls -------------------------------------------------------------------------------------

void RapidTask::Impl::call_proc(const std::string& name, const std::vector<Argument>& args,
                                std::size_t line) {
    auto [module, routine] = find_routine(name);
    if (routine != nullptr) {
        if (routine->kind != rapid::RoutineKind::proc)
            throw RuntimeError(line, "'" + name + "' is a " +
                                         std::string(rapid::to_string(routine->kind)) +
                                         ", not a PROC");
        call_routine(module, *routine, args, line);
        return;
    }
    if (io_instruction(name, args, line) || interrupt_instruction(name, args, line) ||
        motion_instruction(name, args, line) || load_instruction(name, args, line))
        return;
    if (const rapid::InstructionInfo* info = rapid::find_instruction(name))
        throw RuntimeError(line, "instruction " + std::string(info->name) +
                                     " is not executed by the simulated controller");
    throw RuntimeError(line, "unknown procedure '" + name + "'");
}

std::optional<RapidTask::Impl::Value> RapidTask::Impl::call_routine(
    const std::shared_ptr<LoadedModule>& module, const rapid::Routine& routine,
    const std::vector<Argument>& args, std::size_t line) {
    if (frames.size() >= 100)  // the controller's call depth is bounded too
        throw RuntimeError(line, "calls nested too deep (recursion in " + routine.name + "?)");
    auto callee = std::make_unique<Frame>();
    callee->module = module;
    callee->routine = &routine;
    callee->line = routine.line;
    // Arguments are evaluated and resolved in the caller's frame.
    const auto positional = rapid::positional_args(args);
    std::size_t next = 0;
    for (const rapid::Param& p : routine.params) {
        const std::string key = rapid::fold(p.name);
        const Expr* arg = nullptr;
        if (p.optional) {
            const Argument* a = rapid::find_optional(args, p.name);
            if (a == nullptr) {
                callee->absent.push_back(key);
                continue;
            }
            if (!a->value) continue;  // a switch: present, no value
            arg = &*a->value;
        } else {
            if (next >= positional.size())
                throw RuntimeError(line, routine.name + ": argument " + p.name + " missing");
            arg = positional[next++];
        }
        if (p.access == rapid::ParamAccess::in) {
            Variable v{.name = p.name, .type = canonical_type(p.type), .value = eval(*arg)};
            if (p.array_dims == 0) {
                std::string why;
                auto fitted = rapid::conform(v.value, v.type, &why);
                if (!fitted)
                    throw RuntimeError(line, routine.name + ": argument " + p.name + ": " + why);
                v.value = std::move(*fitted);
            } else {
                for (const Value* level = &v.value; level->is_items() && level->type.empty() &&
                                                    v.extents.size() < p.array_dims;
                     level = &level->items().front()) {
                    v.extents.push_back(level->items().size());
                    if (level->items().empty()) break;
                }
            }
            callee->locals[key] = std::move(v);
        } else {
            Slot s = resolve(*arg);
            s.what = p.name;
            callee->refs[key] = std::move(s);
        }
    }
    if (next < positional.size())
        throw RuntimeError(line, routine.name + ": too many arguments");

    frames.push_back(std::move(callee));
    const FramePop pop{frames};
    for (const rapid::DataDecl& d : routine.locals) try {
        Variable v{.name = d.name,
                   .type = canonical_type(d.type),
                   .storage = d.storage,
                   .read_only = d.storage == rapid::Storage::constant};
        try {
            v.extents = d.dims.empty() ? std::vector<std::size_t>{}
                        : d.extents.empty()
                            ? rapid::evaluate_extents(d.dims, rapid::EvalContext{})
                            : d.extents;
        } catch (const rapid::EvalError& e) {
            throw RuntimeError(d.line, e.what());
        }
        v.value = initial_value(d, v, [&](const rapid::Expr& init) { return eval(init); });
        frame().locals[rapid::fold(d.name)] = std::move(v);
    } catch (const RuntimeError& e) {
        throw TaskError(located(e.line(), e.what()));  // in the callee's module
    } catch (const rapid::EvalError& e) {
        throw TaskError(located(e.line(), e.what()));
    }
    return_value.reset();
    exec(routine.body);
    std::optional<Value> result = std::move(return_value);
    return_value.reset();
    return result;
}

}  // namespace fibrecell::drivers::sim
