#include "drivers/sim/cell/sim_controller.hpp"

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/parser.hpp"
#include "drivers/abb/rapid/reader.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>
#include <utility>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;

namespace {

// The task's error as a build-log entry. Its text names module and line ("FcChunk0002 line 41:
// target unreachable ..."), which become the entry's own fields; the status's location is the
// fallback.
rws::BuildError error_entry(const TaskStatus& s) {
    rws::BuildError e{.module = s.module, .row = s.line, .message = s.error};
    const std::size_t at = s.error.find(" line ");
    if (at == std::string::npos || at == 0 || s.error.find(' ') < at) return e;
    std::size_t end = at + 6;
    std::size_t row = 0;
    while (end < s.error.size() && s.error[end] >= '0' && s.error[end] <= '9')
        row = row * 10 + static_cast<std::size_t>(s.error[end++] - '0');
    if (end == at + 6 || s.error.compare(end, 2, ": ") != 0) return e;
    e.module = s.error.substr(0, at);
    e.row = row;
    e.message = s.error.substr(end + 2);
    return e;
}

}  // namespace

SimController::SimController(SimControllerOptions options)
    : InMemoryController(options.build), options_(std::move(options)) {
    if (!(options_.time_scale > 0)) throw std::invalid_argument("time scale must be positive");
}

void SimController::attach(RapidTask* task) {
    task_ = task;
}

RapidTask& SimController::task() const {
    if (task_ == nullptr)
        throw rws::BackendError(400, "the simulated controller has no RAPID task");
    return *task_;
}

bool SimController::task_running() const {
    return task_ != nullptr && task_->status().state == TaskState::running;
}

void SimController::await_task(bool running) const {
    // RapidTask::start()/stop() take effect on the task thread; RWS answers once they have, so
    // that an execution state read right after the call is the new one, as on a controller.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (std::chrono::steady_clock::now() < deadline) {
        const TaskState s = task().status().state;
        if (running ? s != TaskState::stopped : s != TaskState::running) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

void SimController::sync_execution_state() {
    set_execution_state(task_running() ? rws::ExecutionState::running
                                       : rws::ExecutionState::stopped);
}

bool SimController::is_hb_timeout(const std::string& name) const {
    return !options_.hb_timeout_symbol.empty() &&
           rapid::same_name(name, options_.hb_timeout_symbol);
}

void SimController::load_module(const std::string& path, bool replace) {
    if (task_running())
        throw rws::BackendError(400, "cannot load HOME:/" + path + " while RAPID is running");
    InMemoryController::load_module(path, replace);  // build checks, build log
    // The base built it: parsing the text again only recovers the name it was loaded under.
    const rapid::ParseResult parsed = rapid::parse_module(read_file(path).value_or(""));
    const std::optional<rapid::Module> loaded =
        parsed.module ? module(parsed.module->name) : std::nullopt;
    if (!loaded) throw rws::BackendError(500, "HOME:/" + path + " vanished while loading");
    try {
        task().load(*loaded);
        for (const rapid::DataDecl& d : loaded->data)
            if (is_hb_timeout(d.name) && d.value && d.value->is_num())
                task().write_data(loaded->name, d.name,
                                  rapid::num_value(d.value->num() * options_.time_scale));
    } catch (const rws::BackendError&) {
        throw;
    } catch (const std::exception& e) {
        InMemoryController::unload_module(loaded->name);
        throw rws::BackendError(400, "the task refused module " + loaded->name + ": " + e.what());
    }
}

void SimController::unload_module(const std::string& module) {
    if (task_running())
        throw rws::BackendError(400, "cannot unload " + module + " while RAPID is running");
    InMemoryController::unload_module(module);
    task().unload(module);
}

std::vector<rws::ModuleInfo> SimController::modules() const {
    const std::vector<rws::ModuleInfo> loaded_over_rws = InMemoryController::modules();
    if (task_ == nullptr) return loaded_over_rws;
    std::vector<rws::ModuleInfo> out;
    for (const std::string& name : task_->status().loaded) {
        rws::ModuleInfo m{.name = name};
        for (const rws::ModuleInfo& r : loaded_over_rws)
            if (rapid::same_name(r.name, name)) m.type = r.type;
        out.push_back(std::move(m));
    }
    return out;
}

std::vector<rws::BuildError> SimController::build_log() const {
    std::vector<rws::BuildError> log = InMemoryController::build_log();
    const TaskStatus s = task_status();
    if (s.state == TaskState::error) log.push_back(error_entry(s));
    return log;
}

void SimController::start(const rws::StartOptions& options) {
    sync_execution_state();
    InMemoryController::start(options);  // cycle, motors on, a main routine
    try {
        task().start();
        await_task(true);
    } catch (const std::exception& e) {
        set_execution_state(rws::ExecutionState::stopped);
        throw rws::BackendError(400, std::string("cannot start RAPID: ") + e.what());
    }
    std::lock_guard lock(mu_);
    injected_error_.clear();
}

void SimController::stop() {
    InMemoryController::stop();
    if (task_ == nullptr) return;
    task_->stop();
    await_task(false);
}

void SimController::reset_pp() {
    sync_execution_state();
    InMemoryController::reset_pp();  // refused while running, needs main
    task().reset_pp();
    std::lock_guard lock(mu_);
    injected_error_.clear();
}

rws::ExecutionInfo SimController::execution() const {
    rws::ExecutionInfo info = InMemoryController::execution();
    info.state = task_running() ? rws::ExecutionState::running : rws::ExecutionState::stopped;
    return info;
}

std::string SimController::read_symbol(const std::string& module, const std::string& name) const {
    rapid::Value v;
    try {
        v = task().read_data(module, name);
    } catch (const std::out_of_range&) {
        return InMemoryController::read_symbol(module, name);  // 404 with the base's message
    }
    if (is_hb_timeout(name) && v.is_num()) v = rapid::num_value(v.num() / options_.time_scale);
    return rapid::to_rapid_text(v);
}

rapid::Value SimController::to_value(const std::string& module, const std::string& name,
                                     const std::string& text) const {
    const std::optional<rapid::Module> m = this->module(module);
    const rapid::DataDecl* d = m ? m->find_data(name) : nullptr;
    if (d == nullptr)
        throw rws::BackendError(404, "no data named " + name + " in module " + module);
    // The base has checked `text` against the type; read it as an initialiser to get the value.
    rapid::ValidateOptions o;
    o.check_module_name = false;
    const rapid::CheckResult r = rapid::check_module(
        "MODULE FcValueProbe\n  PERS " + d->type + " fcValue := " + text + ";\nENDMODULE\n", o);
    if (!r.module || r.module->data.empty() || !r.module->data.front().value)
        throw rws::BackendError(400, "'" + text + "' is not a " + d->type + " value");
    return *r.module->data.front().value;
}

void SimController::write_symbol(const std::string& module, const std::string& name,
                                 const std::string& value) {
    InMemoryController::write_symbol(module, name, value);  // type checks, CONST refused
    rapid::Value v = to_value(module, name, value);
    if (is_hb_timeout(name) && v.is_num()) v = rapid::num_value(v.num() * options_.time_scale);
    try {
        task().write_data(module, name, v);
    } catch (const std::out_of_range& e) {
        throw rws::BackendError(404, e.what());
    } catch (const std::invalid_argument& e) {
        throw rws::BackendError(400, e.what());
    }
}

void SimController::stop_with_error(const std::string& text) {
    {
        std::lock_guard lock(mu_);
        injected_error_ = text;
    }
    if (task_ != nullptr) {
        task_->stop();
        await_task(false);
    }
    set_execution_state(rws::ExecutionState::stopped);
}

TaskStatus SimController::task_status() const {
    TaskStatus s = task_ != nullptr ? task_->status() : TaskStatus{};
    std::lock_guard lock(mu_);
    if (!injected_error_.empty() && s.state != TaskState::running) {
        s.state = TaskState::error;
        s.error = injected_error_;
    }
    return s;
}

}  // namespace fibrecell::drivers::sim
