#include "drivers/sim/rws/in_memory_controller.hpp"

#include <filesystem>

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/reader.hpp"

namespace fibrecell::drivers::sim::rws {

namespace rapid = abb::rapid;

namespace {

// Build-log entries for the errors of `diagnostics` (warnings do not stop a load).
std::vector<BuildError> to_build_log(const std::vector<rapid::Diagnostic>& diagnostics,
                                     const std::string& module) {
    std::vector<BuildError> out;
    for (const rapid::Diagnostic& d : diagnostics) {
        if (d.severity != rapid::Severity::error) continue;
        BuildError e;
        e.module = module;
        e.row = d.line;
        e.message = d.message + " [" + std::string(rapid::to_string(d.rule)) + "]";
        out.push_back(std::move(e));
    }
    return out;
}

std::string symbol_key(std::string_view name) {
    return rapid::fold(name);
}

}  // namespace

InMemoryController::InMemoryController(rapid::ValidateOptions options)
    : options_(std::move(options)) {}

InMemoryController::Loaded* InMemoryController::find_loaded(std::string_view name) {
    for (Loaded& l : task_)
        if (rapid::same_name(l.module.name, name)) return &l;
    return nullptr;
}

const InMemoryController::Loaded* InMemoryController::find_loaded(std::string_view name) const {
    for (const Loaded& l : task_)
        if (rapid::same_name(l.module.name, name)) return &l;
    return nullptr;
}

bool InMemoryController::has_main() const {
    for (const Loaded& l : task_)
        if (const rapid::Routine* r = l.module.find_routine("main");
            r != nullptr && r->kind == rapid::RoutineKind::proc)
            return true;
    return false;
}

bool InMemoryController::write_file(const std::string& path, std::string contents) {
    std::lock_guard lock(mu_);
    const bool created = files_.count(path) == 0;
    files_[path] = std::move(contents);
    return created;
}

std::optional<std::string> InMemoryController::read_file(const std::string& path) const {
    std::lock_guard lock(mu_);
    const auto it = files_.find(path);
    if (it == files_.end()) return std::nullopt;
    return it->second;
}

void InMemoryController::load_module(const std::string& path, bool replace) {
    std::lock_guard lock(mu_);
    build_log_.clear();  // the log describes the last load
    const auto file = files_.find(path);
    if (file == files_.end()) throw BackendError(404, "file HOME:/" + path + " does not exist");
    const std::string& text = file->second;
    const std::string file_name = std::filesystem::path(path).filename().string();
    const std::string stem = std::filesystem::path(path).stem().string();

    // First pass: the module's name (a real controller does not tie it to the file name).
    rapid::ValidateOptions first = options_;
    first.file_name = file_name;
    first.check_module_name = false;
    const rapid::CheckResult parsed = rapid::check_module(text, first);
    if (!parsed.module) {
        build_log_ = to_build_log(parsed.diagnostics, stem);
        throw BackendError(400, "module in HOME:/" + path + " has syntax errors (see build log)");
    }
    const std::string name = parsed.module->name;
    if (find_loaded(name) != nullptr && !replace)
        throw BackendError(400, "a module named " + name + " is already loaded in the task");

    // Second pass: against the other modules of the task.
    rapid::ValidateOptions o = first;
    for (const Loaded& l : task_) {
        if (rapid::same_name(l.module.name, name)) continue;
        o.loaded_modules.push_back(l.module.name);
        for (const rapid::Routine& r : l.module.routines)
            if (!r.local) o.external_routines.push_back(r.name);
        for (const rapid::DataDecl& d : l.module.data)
            if (d.visibility != rapid::Visibility::local)
                o.external_data.push_back({d.name, d.type});
    }
    rapid::CheckResult built = rapid::check_module(text, o);
    if (!built.ok()) {
        build_log_ = to_build_log(built.diagnostics, name);
        throw BackendError(
            400, "module " + name + " in HOME:/" + path + " has build errors (see build log)");
    }

    Loaded loaded{std::move(*built.module), {}};
    for (const rapid::DataDecl& d : loaded.module.data)
        loaded.symbols[symbol_key(d.name)] =
            Symbol{d.type, d.storage, d.value ? rapid::to_rapid_text(*d.value) : std::string()};
    if (Loaded* old = find_loaded(name))
        *old = std::move(loaded);
    else
        task_.push_back(std::move(loaded));
    build_log_.clear();
    pp_at_main_ = false;
}

void InMemoryController::unload_module(const std::string& module) {
    std::lock_guard lock(mu_);
    for (auto it = task_.begin(); it != task_.end(); ++it) {
        if (rapid::same_name(it->module.name, module)) {
            task_.erase(it);
            pp_at_main_ = false;
            return;
        }
    }
    throw BackendError(404, "no module named " + module + " in the task");
}

std::vector<ModuleInfo> InMemoryController::modules() const {
    std::lock_guard lock(mu_);
    std::vector<ModuleInfo> out;
    for (const Loaded& l : task_) {
        bool sys = false;
        for (const std::string& a : l.module.attributes)
            sys = sys || rapid::same_name(a, "SYSMODULE");
        out.push_back({l.module.name, sys ? "SysMod" : "ProgMod"});
    }
    return out;
}

std::vector<BuildError> InMemoryController::build_log() const {
    std::lock_guard lock(mu_);
    return build_log_;
}

void InMemoryController::start(const StartOptions& options) {
    std::lock_guard lock(mu_);
    if (options.cycle != "once" && options.cycle != "forever" && options.cycle != "asis")
        throw BackendError(400, "cycle must be once, forever or asis, not '" + options.cycle + "'");
    if (controller_state_ != ControllerState::motoron)
        throw BackendError(400, "motors are not on (controller state " +
                                    std::string(to_string(controller_state_)) + ")");
    if (!has_main()) throw BackendError(400, "the task has no routine main to run");
    execution_.state = ExecutionState::running;
    if (options.cycle != "asis") execution_.cycle = options.cycle;
    ++start_count_;
}

void InMemoryController::stop() {
    std::lock_guard lock(mu_);
    execution_.state = ExecutionState::stopped;
}

void InMemoryController::reset_pp() {
    std::lock_guard lock(mu_);
    if (execution_.state == ExecutionState::running)
        throw BackendError(400, "cannot move the program pointer while RAPID is running");
    if (!has_main()) throw BackendError(400, "the task has no routine main");
    pp_at_main_ = true;
}

ExecutionInfo InMemoryController::execution() const {
    std::lock_guard lock(mu_);
    return execution_;
}

ControllerState InMemoryController::controller_state() const {
    std::lock_guard lock(mu_);
    return controller_state_;
}

std::string InMemoryController::read_symbol(const std::string& module,
                                            const std::string& name) const {
    std::lock_guard lock(mu_);
    const Loaded* l = find_loaded(module);
    if (l == nullptr) throw BackendError(404, "no module named " + module + " in the task");
    const auto it = l->symbols.find(symbol_key(name));
    if (it == l->symbols.end())
        throw BackendError(404, "no data named " + name + " in module " + module);
    return it->second.value;
}

void InMemoryController::write_symbol(const std::string& module, const std::string& name,
                                      const std::string& value) {
    std::lock_guard lock(mu_);
    Loaded* l = find_loaded(module);
    if (l == nullptr) throw BackendError(404, "no module named " + module + " in the task");
    const auto it = l->symbols.find(symbol_key(name));
    if (it == l->symbols.end())
        throw BackendError(404, "no data named " + name + " in module " + module);
    Symbol& s = it->second;
    if (s.storage == rapid::Storage::constant)
        throw BackendError(400, name + " is a CONST and cannot be written");
    if (value.find_first_of(";\r\n") != std::string::npos)
        throw BackendError(400, "'" + value + "' is not a " + s.type + " value");

    // Check the value against the type by reading it as the initialiser of a one-line module.
    rapid::ValidateOptions o;
    o.check_module_name = false;
    const std::string probe =
        "MODULE FcValueProbe\n  PERS " + s.type + " fcValue := " + value + ";\nENDMODULE\n";
    const rapid::CheckResult r = rapid::check_module(probe, o);
    if (!r.module || r.module->data.size() != 1 || !r.module->data.front().value) {
        std::string why;
        for (const rapid::Diagnostic& d : r.diagnostics)
            if (d.severity == rapid::Severity::error) {
                // "initial value of 'fcValue' does not fit num: expected num, found a string":
                // the part after the probe's name is the reason.
                const auto colon = d.message.find(": ");
                const bool about_probe = d.message.find("fcValue") != std::string::npos;
                why =
                    ": " + (about_probe && colon != std::string::npos ? d.message.substr(colon + 2)
                                                                      : d.message);
                break;
            }
        throw BackendError(400, "'" + value + "' is not a " + s.type + " value" + why);
    }
    s.value = rapid::to_rapid_text(*r.module->data.front().value);
}

void InMemoryController::set_controller_state(ControllerState s) {
    std::lock_guard lock(mu_);
    controller_state_ = s;
}

void InMemoryController::set_execution_state(ExecutionState s) {
    std::lock_guard lock(mu_);
    execution_.state = s;
}

std::optional<rapid::Module> InMemoryController::module(std::string_view name) const {
    std::lock_guard lock(mu_);
    const Loaded* l = find_loaded(name);
    if (l == nullptr) return std::nullopt;
    return l->module;
}

std::vector<std::string> InMemoryController::files() const {
    std::lock_guard lock(mu_);
    std::vector<std::string> out;
    for (const auto& [path, contents] : files_) out.push_back(path);
    return out;
}

bool InMemoryController::program_pointer_at_main() const {
    std::lock_guard lock(mu_);
    return pp_at_main_;
}

int InMemoryController::start_count() const {
    std::lock_guard lock(mu_);
    return start_count_;
}

}  // namespace fibrecell::drivers::sim::rws
