#pragma once
// The controller behind RwsServer: what the RWS subset reads and changes, with no HTTP in sight.
// The server owns the protocol (digest auth, sessions, RAPID mastership, paths, JSON); a backend
// owns the controller's state. InMemoryController (in_memory_controller.hpp) is the default; the
// simulated cell (drivers/sim) derives from it or implements this interface to execute programs.
//
// Calls arrive on the server's I/O thread, one at a time, while a simulator may change its state
// from other threads: implementations must be thread-safe and must not block for long.
// To refuse an operation, throw BackendError with the HTTP status RWS would answer (400 refused
// in this state or bad value, 404 no such file/module/symbol); its message reaches the client.

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/abb/rws/rws_types.hpp"

namespace fibrecell::drivers::sim::rws {

// The protocol's values (drivers/abb/rws/rws_types.hpp), the same the client reads.
using abb::rws::BuildError;
using abb::rws::ControllerState;
using abb::rws::ExecutionInfo;
using abb::rws::ExecutionState;
using abb::rws::ModuleInfo;
using abb::rws::StartOptions;
using abb::rws::format;
using abb::rws::to_string;

class BackendError : public std::runtime_error {
  public:
    BackendError(int http_status, const std::string& message, long long rws_code = -1)
        : std::runtime_error(message), http_status_(http_status), rws_code_(rws_code) {}
    int http_status() const { return http_status_; }
    long long rws_code() const { return rws_code_; }

  private:
    int http_status_;
    long long rws_code_;  // the controller return code reported in the status body
};

class RwsBackend {
  public:
    virtual ~RwsBackend() = default;

    // HOME: file system. `path` is relative to HOME ("Print_0001.mod", "chunks/P2.mod"),
    // '/'-separated and already checked by the server (no "..", not empty).
    // write_file returns true when the file was created, false when it replaced one.
    virtual bool write_file(const std::string& path, std::string contents) = 0;
    virtual std::optional<std::string> read_file(const std::string& path) const = 0;

    // The RAPID task (T_ROB1; the server answers 404 for other tasks).
    // load_module: read HOME:/`path`, build it and add it to the task (replacing a module of the
    // same name when `replace`). A module that does not build is not loaded: throw BackendError
    // 400 and make build_log() list the errors with their lines.
    virtual void load_module(const std::string& path, bool replace) = 0;
    virtual void unload_module(const std::string& module) = 0;
    virtual std::vector<ModuleInfo> modules() const = 0;
    virtual std::vector<BuildError> build_log() const = 0;  // of the last load; empty when fine

    // RAPID execution.
    virtual void start(const StartOptions& options) = 0;
    virtual void stop() = 0;
    virtual void reset_pp() = 0;  // program pointer to main
    virtual ExecutionInfo execution() const = 0;
    virtual ControllerState controller_state() const = 0;

    // RAPID data RAPID/T_ROB1/<module>/<name>, values as RAPID literal text ("5", "[1,2,3]",
    // "\"text\"").
    virtual std::string read_symbol(const std::string& module, const std::string& name) const = 0;
    virtual void write_symbol(const std::string& module, const std::string& name,
                              const std::string& value) = 0;
};

}  // namespace fibrecell::drivers::sim::rws
