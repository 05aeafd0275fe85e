#pragma once
// Robot Web Services 1.0 client for an IRC5 on RobotWare 6 (docs/rws-link.md): the calls the
// robot link needs, synchronous, over one keep-alive HTTP/1.1 connection (Boost.Beast).
//
//   - Authentication: HTTP digest (MD5, qop=auth). The first request draws a 401 challenge; the
//     client answers it and keeps the session cookies RWS sets (-http-session-, ABBCX). Later
//     requests carry the cookies; without them (or once they expire) the digest nonce is reused
//     with nc = 2, 3, ..., and a 401 stale=true is answered once with the new nonce.
//   - Every call either succeeds or throws RwsError (rws_error.hpp) whose message names the
//     controller (host:port), what was attempted and why it failed.
//   - Timeouts: connect_timeout for the TCP connection, request_timeout for each request and its
//     response. A keep-alive connection the controller closed is reopened once, transparently.
//
// Calls may come from several threads: an internal mutex serialises them, so a state poll from
// another thread waits for an upload in progress.
//
//   RwsClient rws({.host = "192.168.125.1", .port = 80});
//   rws.request_mastership();
//   rws.upload_file("Print_0001.mod", text);
//   rws.load_module("Print_0001.mod");        // RwsError{build} with module, line and message
//   rws.release_mastership();
//   rws.start_execution();

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rws/rws_error.hpp"
#include "drivers/abb/rws/rws_types.hpp"

namespace fibrecell::drivers::abb::rws {

struct RwsClientConfig {
    std::string host = "127.0.0.1";
    std::uint16_t port = 80;
    std::string user = "Default User";  // RobotWare's default UAS user
    std::string password = "robotics";
    std::string task = "T_ROB1";
    std::chrono::milliseconds connect_timeout{2000};
    std::chrono::milliseconds request_timeout{5000};  // per request, uploads included
};

struct RwsClientStats {
    std::uint64_t requests = 0;       // HTTP requests sent, retries included
    std::uint64_t challenges = 0;     // 401 challenges answered
    std::uint64_t stale_retries = 0;  // of which stale=true
    std::uint64_t connects = 0;       // TCP connections opened
};

class RwsClient {
  public:
    explicit RwsClient(RwsClientConfig config);
    ~RwsClient();
    RwsClient(const RwsClient&) = delete;
    RwsClient& operator=(const RwsClient&) = delete;

    // PUT /fileservice/$HOME/<path>: `path` relative to HOME ("Print_0001.mod").
    void upload_file(const std::string& path, std::string_view contents);
    // GET /fileservice/$HOME/<path>.
    std::string download_file(const std::string& path);

    // POST /rw/rapid/tasks/<task>?action=loadmod, modulepath=$HOME/<path>&replace=...; then the
    // task's build log. Needs RAPID mastership. A module that fails to build throws
    // RwsError{build} naming the module, the line and the controller's message (all entries in
    // RwsError::build_errors()).
    void load_module(const std::string& path, bool replace = true);
    // POST ...?action=unloadmod, module=<name>. Needs RAPID mastership.
    void unload_module(const std::string& module);
    // GET /rw/rapid/modules?task=<task>.
    std::vector<ModuleInfo> modules();
    // GET /rw/rapid/tasks/<task>/program/builderror.
    std::vector<BuildError> build_errors();

    // POST /rw/rapid/execution?action=start|stop|resetpp (resetpp needs RAPID mastership).
    void start_execution(const StartOptions& options = {});
    void stop_execution();
    void reset_program_pointer();

    // POST /rw/mastership?action=request|release.
    void request_mastership();
    void release_mastership();
    bool holds_mastership() const;  // as far as this client knows

    // GET /rw/rapid/execution, GET /rw/panel/ctrlstate.
    ExecutionInfo execution_state();
    ControllerState controller_state();

    // RAPID data RAPID/<task>/<module>/<name> as RAPID text ("5", "[1,2,3]", "\"abc\"").
    // Writing needs RAPID mastership.
    void set_symbol(const std::string& module, const std::string& name, const std::string& value);
    std::string symbol(const std::string& module, const std::string& name);

    // GET /logout: ends the controller session (IRC5s have a limited number); the next call
    // logs in again.
    void logout();

    RwsClientStats stats() const;
    std::string endpoint() const;  // "host:port"

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::abb::rws
