// Interrupt instructions of the simulated RAPID task: the intnum variable holds the number
// CONNECT gave it; the table (interrupts.hpp) does the rest.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/names.hpp"

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::Interrupt;
using rapid_exec::RuntimeError;

bool RapidTask::Impl::interrupt_instruction(const std::string& name,
                                            const std::vector<Argument>& args, std::size_t line) {
    const std::string f = rapid::fold(name);
    const auto pos = rapid::positional_args(args);
    auto expect = [&](std::size_t n) { rapid_exec::expect_args(pos, n, name, line); };
    // The connected interrupt an intnum argument names.
    auto connected = [&](const Expr& e) -> std::pair<std::int64_t, Interrupt*> {
        const std::int64_t n = rapid_exec::interrupt_number(eval(e));
        Interrupt* i = interrupts.find(n);
        if (i == nullptr)
            throw RuntimeError(line, name + ": the interrupt is not connected (ERR_UNKINO)");
        return {n, i};
    };
    const bool single = rapid::find_optional(args, "Single") != nullptr ||
                        rapid::find_optional(args, "SingleSafe") != nullptr;

    if (f == "idelete") {
        expect(1);
        const rapid_exec::Slot s = resolve(*pos[0]);
        interrupts.remove(rapid_exec::interrupt_number(*s.value));
        rapid_exec::assign(s, rapid::num_value(0), line);
        return true;
    }
    if (f == "isignaldi" || f == "isignaldo") {
        expect(3);
        const std::string signal = signal_name(*pos[0]);
        read_signal(signal, line);  // an unknown signal is an error now, not at the first edge
        const double edge = eval_num(*pos[1]);
        if (edge != 0 && edge != 1)
            throw RuntimeError(line, name + ": the edge value must be 0 or 1");
        auto [n, i] = connected(*pos[2]);
        if (i->source != Interrupt::Source::none)
            throw RuntimeError(line, name + ": the interrupt is already in use (ERR_ALRDY_ORD)");
        i->source = Interrupt::Source::signal_di;
        i->signal = signal;
        i->edge = edge;
        i->single = single;
        return true;
    }
    if (f == "isignalgi") {
        expect(2);
        const std::string signal = signal_name(*pos[0]);
        read_signal(signal, line);
        auto [n, i] = connected(*pos[1]);
        if (i->source != Interrupt::Source::none)
            throw RuntimeError(line, name + ": the interrupt is already in use (ERR_ALRDY_ORD)");
        i->source = Interrupt::Source::signal_gi;
        i->signal = signal;
        i->single = single;
        return true;
    }
    if (f == "itimer") {
        expect(2);
        const double period = eval_num(*pos[0]);
        if (period < 0.1) throw RuntimeError(line, "ITimer: the period must be at least 0.1 s");
        auto [n, i] = connected(*pos[1]);
        if (i->source != Interrupt::Source::none)
            throw RuntimeError(line, name + ": the interrupt is already in use (ERR_ALRDY_ORD)");
        i->source = Interrupt::Source::timer;
        i->period_s = period;
        i->due_s = clock.now_s() + period;
        i->single = single;
        next_timer_s = std::min(next_timer_s, i->due_s);
        return true;
    }
    if (f == "isleep" || f == "iwatch") {
        expect(1);
        connected(*pos[0]).second->asleep = f == "isleep";
        return true;
    }
    if (f == "idisable" || f == "ienable") {
        expect(0);
        interrupts.set_enabled(f == "ienable");
        return true;
    }
    return false;
}

}  // namespace fibrecell::drivers::sim
