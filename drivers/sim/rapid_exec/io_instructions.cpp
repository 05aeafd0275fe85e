// I/O, waiting, arithmetic and program-flow instructions of the simulated RAPID task.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <algorithm>
#include <variant>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::RuntimeError;
using rapid_exec::expect_args;

namespace {

// Setup instructions whose effect the simulated motion does not model (docs/sim-rapid-task.md).
constexpr std::string_view accepted_settings[] = {"AccSet", "VelSet",   "ConfJ",
                                                  "ConfL",  "SingArea", "TPErase"};

}  // namespace

// ---- Helpers shared by the instruction files ---------------------------------------------------

void rapid_exec::expect_args(const std::vector<const abb::rapid::Expr*>& args, std::size_t n,
                             const std::string& name, std::size_t line) {
    if (args.size() != n)
        throw RuntimeError(line, name + " expects " + std::to_string(n) + " arguments, found " +
                                     std::to_string(args.size()));
}

std::string RapidTask::Impl::signal_name(const Expr& e) {
    const auto* n = std::get_if<rapid::NameRef>(&e.node);
    if (n == nullptr) throw RuntimeError(e.line, "a signal name is expected here");
    return n->name;
}

double RapidTask::Impl::read_signal(const std::string& signal, std::size_t line) {
    if (!io.read_signal) throw RuntimeError(line, "no I/O: cannot read " + signal);
    try {
        return io.read_signal(signal);
    } catch (const std::out_of_range&) {
        throw RuntimeError(line, "unknown signal '" + signal + "'");
    }
}

void RapidTask::Impl::write_signal(const std::string& signal, double value, std::size_t line) {
    if (!io.write_signal) throw RuntimeError(line, "no I/O: cannot write " + signal);
    try {
        io.write_signal(signal, value);
    } catch (const std::out_of_range&) {
        throw RuntimeError(line, "unknown signal '" + signal + "'");
    }
}

double RapidTask::Impl::eval_num(const Expr& e) {
    const Value v = eval(e);
    if (!v.is_num()) throw RuntimeError(e.line, "a num is expected, found " + rapid::to_rapid_text(v));
    return v.num();
}

std::string RapidTask::Impl::eval_string(const Expr& e) {
    const Value v = eval(e);
    if (!v.is_string())
        throw RuntimeError(e.line, "a string is expected, found " + rapid::to_rapid_text(v));
    return v.string();
}

std::optional<double> RapidTask::Impl::optional_num(const std::vector<Argument>& args,
                                                    const char* name) {
    const Argument* a = rapid::find_optional(args, name);
    if (a == nullptr) return std::nullopt;
    if (!a->value) throw RuntimeError(a->line, std::string("\\") + name + " needs a value");
    return eval_num(*a->value);
}

void RapidTask::Impl::timed_out(const std::vector<Argument>& args, const std::string& instruction,
                                std::size_t line) {
    const Argument* flag = rapid::find_optional(args, "TimeFlag");
    if (flag == nullptr || !flag->value)
        throw RuntimeError(line, instruction + ": \\MaxTime expired (ERR_WAIT_MAXTIME)");
    rapid_exec::assign(resolve(*flag->value), rapid::bool_value(true), line);
}

// ---- The instructions --------------------------------------------------------------------------

bool RapidTask::Impl::io_instruction(const std::string& name, const std::vector<Argument>& args,
                                     std::size_t line) {
    const std::string f = rapid::fold(name);
    const auto pos = rapid::positional_args(args);
    for (std::string_view s : accepted_settings)
        if (rapid::same_name(s, name)) return true;

    if (f == "setdo" || f == "setgo" || f == "setao") {
        expect_args(pos, 2, name, line);
        if (rapid::find_optional(args, "SDelay") || rapid::find_optional(args, "Sync"))
            throw RuntimeError(line, name + ": \\SDelay and \\Sync are not executed");
        write_signal(signal_name(*pos[0]), eval_num(*pos[1]), line);
        return true;
    }
    if (f == "set" || f == "reset") {
        expect_args(pos, 1, name, line);
        write_signal(signal_name(*pos[0]), f == "set" ? 1 : 0, line);
        return true;
    }
    if (f == "tpwrite") {
        expect_args(pos, 1, name, line);
        std::string text = eval_string(*pos[0]);
        for (const Argument& a : args)
            if (!a.positional() && a.value) text += rapid::to_rapid_text(eval(*a.value));
        if (io.log) io.log(text);
        return true;
    }
    if (f == "waitdi" || f == "waitdo" || f == "waitgi" || f == "waitgo") {
        expect_args(pos, 2, name, line);
        const std::string signal = signal_name(*pos[0]);
        const double wanted = eval_num(*pos[1]);
        const bool noteq = rapid::find_optional(args, "NOTEQ") != nullptr;
        const bool lt = rapid::find_optional(args, "LT") != nullptr;
        const bool gt = rapid::find_optional(args, "GT") != nullptr;
        const double timeout = optional_num(args, "MaxTime").value_or(forever);
        const bool ok = wait_for(
            [&] {
                const double v = read_signal(signal, line);
                return noteq ? v != wanted : lt ? v < wanted : gt ? v > wanted : v == wanted;
            },
            timeout, 0.004 * clock.time_scale());
        if (!ok) timed_out(args, name, line);
        else if (const Argument* flag = rapid::find_optional(args, "TimeFlag"); flag && flag->value)
            rapid_exec::assign(resolve(*flag->value), rapid::bool_value(false), line);
        return true;
    }
    if (f == "waituntil") {
        expect_args(pos, 1, name, line);
        const double timeout = optional_num(args, "MaxTime").value_or(forever);
        const double poll = std::max(0.01, optional_num(args, "PollRate").value_or(0.1));
        const double start = clock.now_s();
        bool ok = true;
        if (rapid::find_optional(args, "InPos") != nullptr)
            ok = wait_for([&] { return motion.in_position(); }, timeout, motion_poll_s());
        if (ok) {
            const double left = timeout - (clock.now_s() - start);
            ok = wait_for(
                [&] {
                    const Value c = eval(*pos[0]);
                    if (!c.is_bool()) throw RuntimeError(line, "WaitUntil condition is not a bool");
                    return c.boolean();
                },
                left, poll);
        }
        if (!ok) timed_out(args, name, line);
        else if (const Argument* flag = rapid::find_optional(args, "TimeFlag"); flag && flag->value)
            rapid_exec::assign(resolve(*flag->value), rapid::bool_value(false), line);
        return true;
    }
    if (f == "waittime") {
        expect_args(pos, 1, name, line);
        const double t = eval_num(*pos[0]);
        if (t < 0) throw RuntimeError(line, "WaitTime of a negative time");
        if (rapid::find_optional(args, "InPos") != nullptr)
            wait_for([&] { return motion.in_position(); }, forever, motion_poll_s());
        wait_for([] { return false; }, t, t);
        return true;
    }
    if (f == "incr" || f == "decr" || f == "clear") {
        expect_args(pos, 1, name, line);
        const rapid_exec::Slot s = resolve(*pos[0]);
        if (!s.value->is_num()) throw RuntimeError(line, name + " needs a num");
        const double v = f == "clear" ? 0 : s.value->num() + (f == "incr" ? 1 : -1);
        rapid_exec::assign(s, rapid::num_value(v), line);
        return true;
    }
    if (f == "add") {
        expect_args(pos, 2, name, line);
        const rapid_exec::Slot s = resolve(*pos[0]);
        if (!s.value->is_num()) throw RuntimeError(line, name + " needs a num");
        rapid_exec::assign(s, rapid::num_value(s.value->num() + eval_num(*pos[1])), line);
        return true;
    }
    if (f == "stop") {
        // As stop() from outside: the program halts here, start() continues after it.
        {
            const std::lock_guard g(inbox_mu);
            want_run = false;
            ++inbox_seq;
        }
        motion.stop_move();
        task_stopmove = true;
        if (io.log) io.log(located(line, "Stop"));
        return true;  // the next checkpoint parks
    }
    if (f == "exitcycle") {
        // The controller clears the path of the cycle it breaks off.
        if (motion.status().pending > 0) {
            motion.stop_move();
            motion.clear_path();
            if (!program_stopmove && !task_stopmove) motion.start_move();
        }
        throw rapid_exec::ExitCycleSignal{};
    }
    return false;
}

}  // namespace fibrecell::drivers::sim
