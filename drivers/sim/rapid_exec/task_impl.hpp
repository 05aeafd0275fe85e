#pragma once
// Inside RapidTask: the executor's state and its parts, one concern per source file:
//   task_thread.cpp          the thread, start/stop/park, checkpoints between statements, waits
//   rapid_task.cpp           the public API (load, reset_pp, data access, status)
//   statements.cpp           statements
//   calls.cpp                routine calls, name and routine lookup, expressions
//   io_instructions.cpp      SetDO/SetGO, waits, TPWrite, Incr, Stop, ExitCycle, no-op settings
//   interrupt_instructions.cpp  IDelete, ISignalDI/GI, ITimer, ISleep/IWatch, IDisable/IEnable
//   motion_instructions.cpp  MoveL/MoveJ/TriggL/TriggJ, TriggIO/TriggEquip, StopMove, ClearPath
//   loading.cpp              StartLoad/WaitLoad/UnLoad/Load, IsFile
//
// Locks, always taken in this order: state_mu (modules, frames, interrupts: held by the task
// thread while it executes, released while it waits or is stopped), then inbox_mu (requests and
// input changes from other threads), status_mu (what status() shows). TaskIo and the
// MotionSimulator are called without inbox_mu and status_mu held.

#include "drivers/sim/rapid_exec/interrupts.hpp"
#include "drivers/sim/rapid_exec/rapid_task.hpp"
#include "drivers/sim/rapid_exec/task_data.hpp"

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/reader.hpp"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace fibrecell::drivers::sim {

namespace rapid_exec {

// A run-time error with its place: "FcChunk0002 line 41: ...". Passes through every frame.
class TaskError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Control transfers that unwind the executor's stack (not errors).
struct ExitCycleSignal {};  // ExitCycle: restart main, data kept
struct ExitSignal {};       // EXIT: the program ends, program pointer lost
struct RestartSignal {};    // reset_pp() while stopped inside the program
struct QuitSignal {};       // the task is being destroyed

// StartLoad done, WaitLoad not yet: the module is read and validated on a thread of its own
// (as the controller loads in the background), so the task's interrupts (FcMain's heartbeat)
// go on meanwhile.
struct PendingLoad {
    std::string path;
    bool dynamic = false;
    std::shared_future<abb::rapid::CheckResult> checked;
};

// Trigger outputs fire on the motion thread, possibly after the task is gone (the robot still
// moving along queued segments): the gate closes in the task's destructor, and a firing holds it
// while it writes.
struct TriggerGate {
    std::mutex mu;
    bool open = true;
};

}  // namespace rapid_exec

struct RapidTask::Impl {
    using Value = abb::rapid::Value;
    using Expr = abb::rapid::Expr;
    using Argument = abb::rapid::Argument;
    using Flow = bool;  // true: RETURN executed
    static constexpr double forever = std::numeric_limits<double>::infinity();

    Impl(const SimClock& c, MotionSimulator& m, TaskIo i)
        : clock(c), motion(m), io(std::move(i)) {}

    const SimClock& clock;
    MotionSimulator& motion;
    TaskIo io;

    // ---- program state (state_mu) ----
    mutable std::mutex state_mu;
    std::atomic<int> data_waiters{0};  // other threads waiting for state_mu
    std::unique_lock<std::mutex> lock;  // the task thread's hold on state_mu
    std::vector<std::shared_ptr<rapid_exec::LoadedModule>> modules;  // load order
    std::vector<std::unique_ptr<rapid_exec::Frame>> frames;
    rapid_exec::InterruptTable interrupts;
    std::map<std::string, rapid_exec::PendingLoad> loads;  // by load session key
    std::map<std::string, rapid_exec::Variable> predefined;  // copies of predefined data used
    std::optional<Value> return_value;
    Value signal_scratch;
    double next_timer_s = forever;
    bool in_trap = false;
    bool restart_pending = false;
    std::uint64_t seen_seq = 0;

    // ---- requests from other threads (inbox_mu) ----
    std::mutex inbox_mu;
    std::condition_variable inbox_cv;
    bool want_run = false;
    bool quit = false;
    bool thread_active = false;  // the thread executes (not waiting for start)
    std::uint64_t inbox_seq = 0;  // bumped on every request, input change and data write
    std::deque<std::pair<std::string, double>> signal_events;
    std::atomic<bool> program_stopmove{false};  // StopMove by the program in effect
    std::atomic<bool> task_stopmove{false};     // StopMove by stop() or an error in effect

    // ---- what status() shows (status_mu) ----
    mutable std::mutex status_mu;
    TaskStatus shown;

    std::mutex thread_mu;
    std::thread thread;
    std::shared_ptr<rapid_exec::TriggerGate> trigger_gate =
        std::make_shared<rapid_exec::TriggerGate>();

    // ---- task_thread.cpp ----
    void thread_main();
    void run_main();
    void fail(const std::string& message);
    void set_state(TaskState state);
    void publish_loaded();
    void bump_inbox();
    // Between statements: input changes to interrupts, timers, stop requests (parks the thread
    // until start), pending TRAPs. Throws the control signals.
    void checkpoint();
    void park();
    void run_traps();
    // Waits (with checkpoints) until `done` holds or `timeout_s` of simulated time passes;
    // `poll_s` is the longest simulated time between two evaluations of `done`.
    bool wait_for(const std::function<bool()>& done, double timeout_s, double poll_s);
    double motion_poll_s() const;

    // ---- statements.cpp, calls.cpp ----
    rapid_exec::Frame& frame() { return *frames.back(); }
    Flow exec(const abb::rapid::Block& block);
    Flow exec(const abb::rapid::Statement& s);
    void call_proc(const std::string& name, const std::vector<Argument>& args, std::size_t line);
    std::optional<Value> call_routine(const std::shared_ptr<rapid_exec::LoadedModule>& module,
                                      const abb::rapid::Routine& routine,
                                      const std::vector<Argument>& args, std::size_t line);
    std::pair<std::shared_ptr<rapid_exec::LoadedModule>, const abb::rapid::Routine*> find_routine(
        const std::string& name);
    std::optional<rapid_exec::Slot> find_slot(const std::string& name);
    rapid_exec::Slot resolve(const Expr& target);
    Value eval(const Expr& e);
    std::optional<Value> call_function(const abb::rapid::FunctionCall& f, std::size_t line);
    Value current_robtarget(const abb::rapid::FunctionCall& f, std::size_t line);
    std::string located(std::size_t line, const std::string& message);

    // ---- instruction helpers (io_instructions.cpp) ----
    // The signal an argument names (a plain name); throws RuntimeError otherwise.
    std::string signal_name(const Expr& e);
    double read_signal(const std::string& signal, std::size_t line);
    void write_signal(const std::string& signal, double value, std::size_t line);
    double eval_num(const Expr& e);
    std::string eval_string(const Expr& e);
    std::optional<double> optional_num(const std::vector<Argument>& args, const char* name);
    // \MaxTime expired: sets \TimeFlag or raises the error the controller would.
    void timed_out(const std::vector<Argument>& args, const std::string& instruction,
                   std::size_t line);

    bool io_instruction(const std::string& name, const std::vector<Argument>& args,
                        std::size_t line);
    bool interrupt_instruction(const std::string& name, const std::vector<Argument>& args,
                               std::size_t line);
    bool motion_instruction(const std::string& name, const std::vector<Argument>& args,
                            std::size_t line);
    bool load_instruction(const std::string& name, const std::vector<Argument>& args,
                          std::size_t line);
    std::optional<std::string> read_file(const std::string& path, std::size_t line);
};

}  // namespace fibrecell::drivers::sim
