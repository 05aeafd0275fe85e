#pragma once
// The default RwsBackend: a controller that keeps everything in memory and runs nothing.
//   - HOME: is a map from path to file contents.
//   - load_module builds the file with the project's RAPID reader (drivers/abb/rapid/reader.hpp)
//     against the modules already in the task (their global routines and data are visible, as in
//     a real task); any error refuses the load and fills the build log with the lines.
//   - start needs motors on (controller state motoron) and a routine `main` in the task; the
//     execution then stays `running` until stop() or the simulator says otherwise.
//   - module-level data become symbols, their initial values as RAPID text; writes to PERS and
//     VAR data are checked against the declared type, CONST data are read-only.
// The simulated cell drives the rest through the simulator API below, or derives from this class
// (override start()/stop() and call the base) to execute the loaded modules.

#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/program.hpp"
#include "drivers/abb/rapid/validate.hpp"
#include "drivers/sim/rws/rws_backend.hpp"

namespace fibrecell::drivers::sim::rws {

class InMemoryController : public RwsBackend {
  public:
    // `options` is the template for building modules: known_signals (the EIO configuration),
    // max_lines, ... file_name, loaded_modules and the external names are filled per load.
    explicit InMemoryController(abb::rapid::ValidateOptions options = {});

    // RwsBackend
    bool write_file(const std::string& path, std::string contents) override;
    std::optional<std::string> read_file(const std::string& path) const override;
    void load_module(const std::string& path, bool replace) override;
    void unload_module(const std::string& module) override;
    std::vector<ModuleInfo> modules() const override;
    std::vector<BuildError> build_log() const override;
    void start(const StartOptions& options) override;
    void stop() override;
    void reset_pp() override;
    ExecutionInfo execution() const override;
    ControllerState controller_state() const override;
    std::string read_symbol(const std::string& module, const std::string& name) const override;
    void write_symbol(const std::string& module, const std::string& name,
                      const std::string& value) override;

    // Simulator API (thread-safe).
    void set_controller_state(ControllerState s);
    void set_execution_state(ExecutionState s);  // e.g. the program reached its end
    std::optional<abb::rapid::Module> module(std::string_view name) const;  // as loaded
    std::vector<std::string> files() const;
    bool program_pointer_at_main() const;  // set by reset_pp, cleared by load/unload
    int start_count() const;

  protected:
    mutable std::mutex mu_;  // guards everything below; derived classes may take it too

  private:
    struct Symbol {
        std::string type;
        abb::rapid::Storage storage = abb::rapid::Storage::var;
        std::string value;
    };
    struct Loaded {
        abb::rapid::Module module;
        std::map<std::string, Symbol> symbols;  // by folded name
    };

    abb::rapid::ValidateOptions options_;
    std::map<std::string, std::string> files_;
    std::vector<Loaded> task_;  // in load order
    std::vector<BuildError> build_log_;
    ExecutionInfo execution_;
    ControllerState controller_state_ = ControllerState::motoron;
    bool pp_at_main_ = false;
    int start_count_ = 0;

    Loaded* find_loaded(std::string_view name);
    const Loaded* find_loaded(std::string_view name) const;
    bool has_main() const;
};

}  // namespace fibrecell::drivers::sim::rws
