// The task thread of the simulated RAPID task: waits for start, runs main, parks at a statement
// boundary when stopped, serves interrupts between statements and while an instruction waits.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <algorithm>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::RuntimeError;
using rapid_exec::TaskError;

void RapidTask::Impl::set_state(TaskState state) {
    const std::lock_guard g(status_mu);
    shown.state = state;
    if (state == TaskState::running) shown.error.clear();
}

void RapidTask::Impl::publish_loaded() {
    std::vector<std::string> names;
    for (const auto& m : modules) names.push_back(m->name());
    const std::lock_guard g(status_mu);
    shown.loaded = std::move(names);
}

void RapidTask::Impl::bump_inbox() {
    const std::lock_guard g(inbox_mu);
    ++inbox_seq;
    inbox_cv.notify_all();
}

void RapidTask::Impl::fail(const std::string& message) {
    {
        const std::lock_guard g(inbox_mu);
        want_run = false;
    }
    // An execution error stops the robot as well; start() lets it go on.
    motion.stop_move();
    task_stopmove = true;
    {
        const std::lock_guard g(status_mu);
        shown.state = TaskState::error;
        shown.error = message;
    }
    if (io.log) io.log("RAPID task error: " + message);
}

void RapidTask::Impl::run_main() {
    std::shared_ptr<rapid_exec::LoadedModule> module;
    const abb::rapid::Routine* main = nullptr;
    for (const auto& m : modules)
        if (const auto* r = m->module->find_routine("main");
            r != nullptr && !r->local && r->kind == rapid::RoutineKind::proc) {
            module = m;
            main = r;
            break;
        }
    if (main == nullptr) throw TaskError("no main routine in the task");
    in_trap = false;
    call_routine(module, *main, {}, main->line);
}

void RapidTask::Impl::thread_main() {
    lock = std::unique_lock(state_mu);
    for (;;) {
        lock.unlock();
        {
            std::unique_lock il(inbox_mu);
            thread_active = false;
            inbox_cv.wait(il, [&] { return want_run || quit; });
            if (quit) return;
            thread_active = true;
        }
        lock.lock();
        restart_pending = false;
        set_state(TaskState::running);
        for (bool again = true; again;) {
            again = false;
            try {
                run_main();
                {  // main returned: the program ends
                    const std::lock_guard g(inbox_mu);
                    want_run = false;
                }
                set_state(TaskState::stopped);
            } catch (const rapid_exec::ExitCycleSignal&) {
                again = true;
            } catch (const rapid_exec::RestartSignal&) {
                again = true;
            } catch (const rapid_exec::ExitSignal&) {
                {
                    const std::lock_guard g(inbox_mu);
                    want_run = false;
                }
                set_state(TaskState::stopped);
            } catch (const rapid_exec::QuitSignal&) {
                lock.unlock();
                return;
            } catch (const std::exception& e) {
                fail(e.what());
            }
            frames.clear();
            return_value.reset();
            in_trap = false;
        }
        const std::lock_guard g(status_mu);
        shown.module.clear();
        shown.line = 0;
    }
}

void RapidTask::Impl::checkpoint() {
    // Let a thread waiting for the data (read_data, write_data, reset_pp) in.
    if (data_waiters.load() > 0) {
        lock.unlock();
        std::this_thread::yield();
        lock.lock();
    }
    std::deque<std::pair<std::string, double>> events;
    bool run = false;
    {
        const std::lock_guard g(inbox_mu);
        if (quit) throw rapid_exec::QuitSignal{};
        events.swap(signal_events);
        run = want_run;
        seen_seq = inbox_seq;
    }
    for (const auto& [signal, value] : events) interrupts.signal_changed(signal, value);
    if (!run) park();
    next_timer_s = interrupts.timers_due(clock.now_s());
    if (!in_trap) run_traps();
}

void RapidTask::Impl::park() {
    set_state(TaskState::stopped);
    lock.unlock();
    {
        std::unique_lock il(inbox_mu);
        thread_active = false;
        inbox_cv.wait(il, [&] { return want_run || quit; });
        thread_active = true;
    }
    lock.lock();
    {
        const std::lock_guard g(inbox_mu);
        if (quit) throw rapid_exec::QuitSignal{};
    }
    set_state(TaskState::running);
    if (restart_pending) {
        restart_pending = false;
        throw rapid_exec::RestartSignal{};
    }
}

void RapidTask::Impl::run_traps() {
    while (auto number = interrupts.next_pending()) {
        const rapid_exec::Interrupt* i = interrupts.find(*number);
        const auto module = i->module;
        const abb::rapid::Routine* trap = i->trap;
        struct TrapScope {
            bool& flag;
            ~TrapScope() { flag = false; }
        } scope{in_trap};
        in_trap = true;
        call_routine(module, *trap, {}, trap->line);
        // The program pointer is back where the TRAP interrupted.
        const std::lock_guard g(status_mu);
        shown.module = frame().module->name();
        shown.line = frame().line;
    }
}

bool RapidTask::Impl::wait_for(const std::function<bool()>& done, double timeout_s,
                               double poll_s) {
    const double deadline = clock.now_s() + timeout_s;
    for (;;) {
        checkpoint();
        if (done()) return true;
        const double now = clock.now_s();
        if (now >= deadline) return false;
        const double wake = std::min({deadline, now + poll_s, next_timer_s});
        lock.unlock();
        {
            std::unique_lock il(inbox_mu);
            inbox_cv.wait_until(il, clock.wall_at(wake), [&] { return inbox_seq != seen_seq; });
        }
        lock.lock();
    }
}

}  // namespace fibrecell::drivers::sim
