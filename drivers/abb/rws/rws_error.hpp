#pragma once
// The one exception the RWS client throws. Its message is meant for an operator: it names the
// controller (host:port), what was attempted and why it failed, e.g.
//   "load module Print_0001 at 10.0.0.5:80: build error in Print_0001 line 12: ..."

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rws/rws_types.hpp"

namespace fibrecell::drivers::abb::rws {

enum class RwsErrorKind {
    auth,        // 401 after the digest handshake and one retry: wrong user or password
    mastership,  // 403, or mastership held by another client
    build,       // a module failed to load, or loaded with build errors (see build_errors())
    not_found,   // 404: file, module, symbol or resource does not exist
    state,       // the controller refused in its current state (motors off, running, ...)
    transport,   // connection refused, reset or timed out
    protocol,    // an unexpected status or a response this client cannot read
};

std::string_view to_string(RwsErrorKind kind);

class RwsError : public std::runtime_error {
  public:
    RwsError(RwsErrorKind kind, const std::string& message, int http_status = 0,
             std::vector<BuildError> build_errors = {})
        : std::runtime_error(message),
          kind_(kind),
          http_status_(http_status),
          build_errors_(std::move(build_errors)) {}

    RwsErrorKind kind() const { return kind_; }
    int http_status() const { return http_status_; }  // 0 when no response was received
    const std::vector<BuildError>& build_errors() const { return build_errors_; }

  private:
    RwsErrorKind kind_;
    int http_status_;
    std::vector<BuildError> build_errors_;
};

}  // namespace fibrecell::drivers::abb::rws
