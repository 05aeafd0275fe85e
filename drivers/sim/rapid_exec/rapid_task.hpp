#pragma once
// A simulated RAPID task (T_ROB1): executes modules read by the project's RAPID reader
// (drivers/abb/rapid) -- the resident main module FcMain and the chunk modules it loads -- on its
// own thread, in simulated time. Motion instructions queue segments on the MotionSimulator;
// I/O instructions and functions go to the TaskIo callbacks; interrupts (ISignalDI, ITimer) run
// their TRAPs between statements and while an instruction waits. The subset executed is the one
// docs/rapid-subset.md accepts, limited to what FcMain and the chunk writer use; anything else is
// a run-time error naming module and line (docs/sim-rapid-task.md lists what is executed).

#include "drivers/abb/rapid/program.hpp"
#include "drivers/abb/rapid/value.hpp"
#include "drivers/sim/motion/motion_simulator.hpp"
#include "drivers/sim/sim_clock.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

// What the task reads and writes besides motion. Called on the task thread while it holds the
// program state; must not block long, and may call back into the task only through
// signal_changed() and status() (read_data, write_data, load, start would wait for the task).
struct TaskIo {
    // Current value of an input or output signal (DInput, GInput, DOutput, GOutput); throws
    // std::out_of_range for an unknown signal name.
    std::function<double(const std::string& signal)> read_signal;
    // SetDO / SetGO / trigger outputs (also called on the motion thread when a trigger fires).
    std::function<void(const std::string& signal, double value)> write_signal;
    // A file on the controller by its RAPID path ("HOME:/fibrecell/job/FcChunk0001.mod");
    // nothing when it does not exist (IsFile, StartLoad, Load).
    std::function<std::optional<std::string>(const std::string& path)> read_file;
    // TPWrite and the task's own messages (errors, stops).
    std::function<void(const std::string& text)> log;
    // The signal names of the I/O configuration (EIO): the modules the program loads itself
    // (StartLoad/WaitLoad) are validated against them, as the controller does when it links.
    std::vector<std::string> known_signals;
};

enum class TaskState { stopped, running, error };

struct TaskStatus {
    TaskState state = TaskState::stopped;
    std::string error;  // the run-time error that stopped the task ("FcChunk0002 line 41: ...")
    std::string module; // where the program pointer is
    std::size_t line = 0;
    std::vector<std::string> loaded;  // module names in the task, load order
};

class RapidTask {
  public:
    RapidTask(const SimClock& clock, MotionSimulator& motion, TaskIo io);
    ~RapidTask();  // stops the task thread
    RapidTask(const RapidTask&) = delete;
    RapidTask& operator=(const RapidTask&) = delete;

    // Modules loaded into the task by the controller (RWS loadmod): resident, not unloaded by the
    // program. Replaces a module of the same name. Only while stopped.
    void load(abb::rapid::Module module);
    void unload(const std::string& module_name);

    // Program pointer to main: data of all modules back to their initial values except PERS;
    // interrupts deleted, modules the program loaded (StartLoad/Load) unloaded, the motion path
    // cleared. Only while stopped (std::logic_error otherwise).
    void reset_pp();
    // Starts (or continues from the program pointer) on the task thread. Throws std::logic_error
    // when there is no main routine. status() shows running as soon as it returns. After an
    // error, EXIT or the end of main, the program starts again at main (data kept).
    void start();
    // Stops execution at the next statement boundary and the motion (StopMove); start() continues.
    // Never blocks: status() shows stopped once the thread has parked.
    void stop();

    // An input changed (the I/O side calls this on every change of a signal the task may watch
    // with ISignalDI/ISignalGI); safe from any thread.
    void signal_changed(const std::string& signal, double value);

    // Module data by module and name, as for RWS symbol reads/writes; safe from any thread while
    // the task runs. Throws std::out_of_range for an unknown symbol, std::invalid_argument for a
    // value that does not fit the declared type or a CONST.
    abb::rapid::Value read_data(const std::string& module, const std::string& name) const;
    void write_data(const std::string& module, const std::string& name,
                    const abb::rapid::Value& value);

    TaskStatus status() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::sim
