// Program-loaded modules of the simulated RAPID task: StartLoad reads the file, WaitLoad reads,
// validates and links it (as the controller does, against the I/O configuration and the modules
// already in the task), UnLoad removes it by its file. Load is StartLoad + WaitLoad.
#include "drivers/sim/rapid_exec/task_impl.hpp"

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/reader.hpp"

#include <algorithm>
#include <chrono>
#include <future>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;
using rapid_exec::RuntimeError;

namespace {

std::string file_part(const std::string& path) {
    const auto slash = path.find_last_of("/:");
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

std::optional<std::string> RapidTask::Impl::read_file(const std::string& path, std::size_t line) {
    if (!io.read_file) throw RuntimeError(line, "no file access: cannot read " + path);
    return io.read_file(path);
}

bool RapidTask::Impl::load_instruction(const std::string& name, const std::vector<Argument>& args,
                                       std::size_t line) {
    const std::string f = rapid::fold(name);
    const auto pos = rapid::positional_args(args);
    auto expect = [&](std::size_t n) { rapid_exec::expect_args(pos, n, name, line); };
    if (rapid::find_optional(args, "File") != nullptr || rapid::find_optional(args, "CheckRef"))
        throw RuntimeError(line, name + ": \\File and \\CheckRef are not executed");

    // Reads the file and starts validating it against the I/O configuration and the modules in
    // the task now (the resident ones do not change while a chunk loads).
    auto start_load = [&](const std::string& path) {
        auto text = read_file(path, line);
        if (!text) throw RuntimeError(line, name + ": no file " + path + " (ERR_FILNOTFND)");
        rapid::ValidateOptions o;
        o.file_name = file_part(path);
        o.known_signals = io.known_signals;
        for (const auto& m : modules) {
            o.loaded_modules.push_back(m->name());
            for (const rapid::Routine& r : m->module->routines)
                if (!r.local && r.kind != rapid::RoutineKind::trap)
                    o.external_routines.push_back(r.name);
            for (const auto& [key, v] : m->data)
                if (!v.local) o.external_data.push_back({v.name, v.type});
        }
        return rapid_exec::PendingLoad{
            .path = path,
            .dynamic = rapid::find_optional(args, "Dynamic") != nullptr,
            .checked = std::async(std::launch::async,
                                  [text = std::move(*text), o = std::move(o)] {
                                      return rapid::check_module(text, o);
                                  })
                           .share()};
    };
    // Waits for the validation (interrupts run meanwhile) and adds the module to the task.
    auto link = [&](const rapid_exec::PendingLoad& load) {
        wait_for([&] { return load.checked.wait_for(std::chrono::seconds(0)) == std::future_status::ready; },
                 1e9, 0.01);
        const rapid::CheckResult& r = load.checked.get();
        for (const rapid::Diagnostic& d : r.diagnostics)
            if (d.severity == rapid::Severity::error)
                throw RuntimeError(line, name + ": " + load.path + " does not link: " +
                                             rapid::format(d));
        if (!r.module) throw RuntimeError(line, name + ": " + load.path + " does not parse");
        auto loaded = rapid_exec::instantiate(std::make_shared<const rapid::Module>(*r.module), true,
                                              load.path);
        modules.push_back(std::move(loaded));
        publish_loaded();
    };

    if (f == "startload") {
        expect(2);
        const std::string path = eval_string(*pos[0]);
        const rapid_exec::Slot session = resolve(*pos[1]);
        if (session.type != "loadsession")
            throw RuntimeError(line, "StartLoad: '" + session.what + "' is not a loadsession");
        loads[path] = start_load(path);
        *session.value = Value{path, "loadsession"};
        return true;
    }
    if (f == "waitload") {
        expect(1);
        const rapid_exec::Slot session = resolve(*pos[0]);
        auto it = session.value->is_string() ? loads.find(session.value->string()) : loads.end();
        if (it == loads.end())
            throw RuntimeError(line, "WaitLoad: no StartLoad on '" + session.what + "'");
        const rapid_exec::PendingLoad load = std::move(it->second);
        loads.erase(it);
        *session.value = Value{std::monostate{}, "loadsession"};
        link(load);
        return true;
    }
    if (f == "load") {
        expect(1);
        link(start_load(eval_string(*pos[0])));
        return true;
    }
    if (f == "unload") {
        expect(1);
        const std::string path = eval_string(*pos[0]);
        auto it = std::find_if(modules.begin(), modules.end(),
                               [&](const auto& m) { return m->path == path; });
        if (it == modules.end())
            throw RuntimeError(line, "UnLoad: no module loaded from " + path + " (ERR_UNLOAD)");
        modules.erase(it);
        publish_loaded();
        return true;
    }
    return false;
}

}  // namespace fibrecell::drivers::sim
