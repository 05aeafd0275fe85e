#pragma once
// The HTTP side of the simulated IRC5: Robot Web Services 1.0 (the subset in rws_routes.hpp)
// over HTTP/1.1 with keep-alive, on Boost.Beast, with
//   - digest authentication (MD5, qop=auth, realm "validusers@robapi.abb", user/password from
//     the config); a nonce lives `nonce_lifetime`, after which right credentials get stale=true;
//   - sessions: a successful digest login opens one and, when `session_cookies`, sets the
//     `-http-session-` and `ABBCX` cookies that RWS uses; later requests may carry only those;
//   - RAPID mastership held per session (released when the session ends), with a knob that makes
//     another client hold it.
// The controller itself is an RwsBackend (rws_backend.hpp). One I/O thread serves every
// connection; the constructor binds and starts it, the destructor stops it.
//
//   auto controller = std::make_shared<InMemoryController>();
//   RwsServer server(controller);                 // 127.0.0.1, ephemeral port
//   RwsClient client({.host = "127.0.0.1", .port = server.port()});

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/sim/rws/rws_backend.hpp"

namespace fibrecell::drivers::sim::rws {

struct RwsServerConfig {
    std::string address = "127.0.0.1";
    std::uint16_t port = 0;  // 0: an ephemeral port, see RwsServer::port()
    std::string user = "Default User";
    std::string password = "robotics";
    std::string realm = "validusers@robapi.abb";
    std::string task = "T_ROB1";
    std::chrono::seconds nonce_lifetime{300};
    bool session_cookies = true;  // false: clients must authenticate every request by digest
    std::size_t max_body_bytes = 64u << 20;         // larger uploads get 413
    std::chrono::milliseconds idle_timeout{60000};  // a connection without a request is closed
};

struct RwsServerStats {
    std::uint64_t requests = 0;          // every request received
    std::uint64_t challenges = 0;        // 401 with a fresh nonce
    std::uint64_t stale_challenges = 0;  // 401 with stale=true
    std::uint64_t rejected = 0;          // Authorization present but wrong
    std::uint64_t digest_logins = 0;     // requests authenticated by digest (not by cookie)
    std::uint64_t sessions_opened = 0;
    std::uint32_t max_nc = 0;  // highest nonce count seen
    std::uint64_t idle_closes = 0;  // connections closed after idle_timeout without a request
};

class RwsServer {
  public:
    // Binds config.address:config.port and starts serving; throws std::runtime_error naming the
    // address when binding fails.
    explicit RwsServer(std::shared_ptr<RwsBackend> backend, RwsServerConfig config = {});
    ~RwsServer();
    RwsServer(const RwsServer&) = delete;
    RwsServer& operator=(const RwsServer&) = delete;

    std::uint16_t port() const;  // the bound port
    const std::string& address() const;
    void stop();  // closes the listener and every connection; idempotent

    // Fault knobs (thread-safe).
    void set_mastership_held_elsewhere(bool held);  // as if the FlexPendant held it
    bool mastership_held() const;                   // by a client session
    void expire_nonces();  // the next use of any current nonce is answered stale=true
    void end_sessions();   // cookies become invalid and mastership is released

    RwsServerStats stats() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::sim::rws
