// Motion instructions of the simulated RAPID task: one MotionSimulator segment per MoveL, MoveJ,
// TriggL, TriggJ; TriggIO/TriggEquip set up the triggers those carry; StopMove, StartMove and
// ClearPath go straight to the simulator.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/instructions.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/robot_data.hpp"

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::RuntimeError;
using rapid_exec::TaskError;

namespace {

// How many fly-by segments RAPID may run ahead of the robot (the controller's look-ahead).
constexpr std::size_t max_run_ahead = 4;

// A trigger as TriggIO/TriggEquip leave it in the triggdata variable:
// [distance, \Start, equipment lag, signal, value].
rapid::Value trigger_value(double distance, bool start, double lag, const std::string& signal,
                           double value) {
    return rapid::items_value({rapid::num_value(distance), rapid::bool_value(start),
                               rapid::num_value(lag), rapid::string_value(signal),
                               rapid::num_value(value)},
                              "triggdata");
}

}  // namespace

double RapidTask::Impl::motion_poll_s() const {
    return 0.002 * clock.time_scale();  // 2 ms of real time
}

bool RapidTask::Impl::motion_instruction(const std::string& name,
                                         const std::vector<Argument>& args, std::size_t line) {
    const std::string f = rapid::fold(name);
    const auto pos = rapid::positional_args(args);
    auto expect = [&](std::size_t n) { rapid_exec::expect_args(pos, n, name, line); };

    if (f == "stopmove") {
        motion.stop_move();
        program_stopmove = true;
        return true;
    }
    if (f == "startmove") {
        program_stopmove = false;
        if (!task_stopmove) motion.start_move();
        return true;
    }
    if (f == "clearpath") {
        motion.clear_path();
        return true;
    }
    if (f == "triggio" || f == "triggequip") {
        const bool equip = f == "triggequip";
        expect(equip ? 4 : 3);
        if (rapid::find_optional(args, "Time") != nullptr)
            throw RuntimeError(line, name + ": \\Time is not executed (distances only)");
        std::string signal;
        for (const char* o : {"DOp", "GOp", "AOp"})
            if (const Argument* a = rapid::find_optional(args, o); a && a->value)
                signal = signal_name(*a->value);
        if (signal.empty()) throw RuntimeError(line, name + ": no \\DOp, \\GOp or \\AOp signal");
        read_signal(signal, line);  // an unknown signal is an error here, not on the motion thread
        const double distance = eval_num(*pos[1]);
        const double lag = equip ? eval_num(*pos[2]) : 0.0;
        const double value = eval_num(*pos[equip ? 3 : 2]);
        const rapid_exec::Slot slot = resolve(*pos[0]);
        if (slot.type != "triggdata")
            throw RuntimeError(line, name + ": '" + slot.what + "' is not a triggdata");
        *slot.value = trigger_value(distance,
                                    rapid::find_optional(args, "Start") != nullptr, lag, signal,
                                    value);
        return true;
    }

    const bool trigg = f == "triggl" || f == "triggj";
    if (!(f == "movel" || f == "movej" || trigg)) return false;
    expect(trigg ? 5 : 4);
    for (const char* o : {"Conc", "ID", "T", "Inpos", "Corr", "TLoad"})
        if (rapid::find_optional(args, o) != nullptr)
            throw RuntimeError(line, name + ": \\" + o + " is not executed");

    const std::size_t zone_at = trigg ? 3 : 2, tool_at = trigg ? 4 : 3;
    MotionSegment segment;
    segment.joint = f == "movej" || f == "triggj";
    auto target = rapid::to_robtarget(eval(*pos[0]));
    auto speed = rapid::to_speeddata(eval(*pos[1]));
    auto zone = rapid::to_zonedata(eval(*pos[zone_at]));
    auto tool = rapid::to_tooldata(eval(*pos[tool_at]));
    if (!target) throw RuntimeError(line, name + ": the target is not a robtarget");
    if (!speed) throw RuntimeError(line, name + ": the speed is not a speeddata");
    if (!zone) throw RuntimeError(line, name + ": the zone is not a zonedata");
    if (!tool) throw RuntimeError(line, name + ": the tool is not a tooldata");
    const Argument* w = rapid::find_optional(args, "WObj");
    auto wobj = rapid::to_wobjdata(w != nullptr && w->value ? eval(*w->value)
                                                            : *find_slot("wobj0")->value);
    if (!wobj) throw RuntimeError(line, name + ": \\WObj is not a wobjdata");
    if (auto v = optional_num(args, "V")) speed->v_tcp_mm_s = *v;
    if (auto z = optional_num(args, "Z")) zone->pzone_tcp_mm = *z;
    segment.target = *target;
    segment.speed = *speed;
    segment.zone = *zone;
    segment.tool = *tool;
    segment.wobj = *wobj;
    segment.source = frame().module->name() + " line " + std::to_string(line);

    if (trigg) {
        std::vector<const Expr*> triggers{pos[2]};
        for (const Argument& a : args)
            if (rapid::is_extra_trigger(a.name) && a.value) triggers.push_back(&*a.value);
        for (const Expr* t : triggers) {
            const Value v = eval(*t);
            if (v.type != "triggdata" || !v.is_items() || v.items().size() != 5)
                throw RuntimeError(line, name + ": a trigger was not set up by TriggIO or "
                                                "TriggEquip");
            const auto& it = v.items();
            auto write = io.write_signal;
            const std::string signal = it[3].string();
            const double value = it[4].num();
            segment.triggers.push_back(MotionTrigger{
                .distance_mm = it[0].num(),
                .from_start = it[1].boolean(),
                .lag_s = it[2].num(),
                .fire = [gate = trigger_gate, write, signal, value] {
                    const std::lock_guard g(gate->mu);
                    if (gate->open) write(signal, value);
                }});
        }
    }

    std::uint64_t id = 0;
    try {
        id = motion.queue(std::move(segment));
    } catch (const MotionError& e) {
        throw TaskError(e.what());  // names module and line already (the segment's source)
    }
    // RAPID runs ahead of the robot, but not past a stop point and not too far.
    const bool stop_point = zone->finep;
    const bool ok = wait_for(
        [&] {
            const MotionStatus s = motion.status();
            if (!s.error.empty()) throw RuntimeError(line, "motion stopped: " + s.error);
            return stop_point ? motion.done(id) : s.pending <= max_run_ahead;
        },
        forever, motion_poll_s());
    (void)ok;
    return true;
}

}  // namespace fibrecell::drivers::sim
