#pragma once
// The simulated IRC5 behind the RWS server: InMemoryController (HOME: files, module build checks,
// symbols, controller state) with the RAPID task executing what it holds. RWS loadmod/unloadmod,
// start/stop/resetpp and symbol reads and writes go to the RapidTask as well; the execution state
// is the task's (stopped after a run-time error). docs/simcell.md.
//
// Two things differ from a plain pass-through:
//   - Heartbeat timeout in simulated time. FcMain counts nFcHbTimeout in simulated seconds, the
//     service's heartbeat runs in real time. Every value of `hb_timeout_symbol` reaching the task
//     (its initial value at load, RWS writes) is multiplied by the time scale, and RWS reads
//     divide it back, so the service sees and sets the real-time timeout it configured.
//   - Run-time errors. The RWS subset has no event log: while the task stands in an error, the
//     error is the last entry of the task's build log (GET .../program/builderror), with module
//     and line. A reset of the program pointer clears it.

#include "drivers/sim/rws/in_memory_controller.hpp"
#include "drivers/sim/rapid_exec/rapid_task.hpp"

#include <string>

namespace fibrecell::drivers::sim {

struct SimControllerOptions {
    abb::rapid::ValidateOptions build;  // module checks: known_signals = the EIO signals
    double time_scale = 1;              // simulated seconds per real second
    std::string hb_timeout_symbol = "nFcHbTimeout";  // num data scaled as above, in any module
};

class SimController : public rws::InMemoryController {
  public:
    explicit SimController(SimControllerOptions options);

    // The task the controller drives (not owned). Until attached, nothing executes.
    void attach(RapidTask* task);

    // RwsBackend
    void load_module(const std::string& path, bool replace) override;
    void unload_module(const std::string& module) override;
    // The task's modules, the chunks FcMain loaded itself included (as RWS lists them).
    std::vector<abb::rws::ModuleInfo> modules() const override;
    std::vector<abb::rws::BuildError> build_log() const override;
    void start(const abb::rws::StartOptions& options) override;
    void stop() override;
    void reset_pp() override;
    abb::rws::ExecutionInfo execution() const override;
    std::string read_symbol(const std::string& module, const std::string& name) const override;
    void write_symbol(const std::string& module, const std::string& name,
                      const std::string& value) override;

    // Fault knobs and the task seen through the controller.
    void stop_with_error(const std::string& text);  // task stopped, the error reported as its own
    TaskStatus task_status() const;                 // the task's, with an injected error on top

  private:
    RapidTask& task() const;
    bool task_running() const;
    void sync_execution_state();  // the base's running/stopped from the task
    // Waits (bounded) until the task thread has taken a start (`running`) or a stop.
    void await_task(bool running) const;
    bool is_hb_timeout(const std::string& name) const;
    abb::rapid::Value to_value(const std::string& module, const std::string& name,
                               const std::string& text) const;

    SimControllerOptions options_;
    RapidTask* task_ = nullptr;
    std::string injected_error_;  // guarded by mu_
};

}  // namespace fibrecell::drivers::sim
