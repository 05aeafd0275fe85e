#pragma once
// The task's interrupt table: CONNECT gives an intnum variable a number tied to a TRAP;
// ISignalDI/ISignalGI subscribe it to an input, ITimer to a simulated-time period. Events raise
// the interrupt into a FIFO of pending TRAP runs; the executor runs them between statements and
// while an instruction waits, one at a time. No thread, no lock: the executor owns it.

#include "drivers/sim/rapid_exec/task_data.hpp"

#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace fibrecell::drivers::sim::rapid_exec {

struct Interrupt {
    std::shared_ptr<LoadedModule> module;  // where the TRAP lives
    const rapid::Routine* trap = nullptr;
    enum class Source { none, signal_di, signal_gi, timer } source = Source::none;
    std::string signal;           // signal_di / signal_gi
    double edge = 0;              // signal_di: the value that raises it
    bool single = false;          // \Single: once, then disarmed
    double period_s = 0;          // timer
    double due_s = 0;             // timer: next expiry (simulated time)
    bool asleep = false;          // ISleep: events are discarded
};

// The interrupt number an intnum value holds; 0 (never connected) for anything that is not a
// whole number in range.
std::int64_t interrupt_number(const rapid::Value& v);

class InterruptTable {
  public:
    // CONNECT: a new interrupt number for the TRAP.
    std::int64_t connect(std::shared_ptr<LoadedModule> module, const rapid::Routine& trap);
    // nullptr for a number that is not connected.
    Interrupt* find(std::int64_t number);
    void remove(std::int64_t number);  // IDelete: also drops its pending runs
    void clear();                      // reset_pp

    // An input changed: raise every interrupt subscribed to it.
    void signal_changed(const std::string& signal, double value);
    // Raise the timers due at `now_s`; returns the next expiry (infinity when none).
    double timers_due(double now_s);

    // IDisable/IEnable: raised interrupts wait in the queue while disabled.
    void set_enabled(bool enabled) { enabled_ = enabled; }
    // The next TRAP to run, taken off the queue; nothing when none is due or disabled.
    std::optional<std::int64_t> next_pending();

  private:
    void raise(std::int64_t number, Interrupt& i);

    std::map<std::int64_t, Interrupt> table_;
    std::deque<std::int64_t> pending_;
    std::int64_t next_number_ = 1;
    bool enabled_ = true;
};

}  // namespace fibrecell::drivers::sim::rapid_exec
