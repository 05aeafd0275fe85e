#pragma once
// JSON-RPC 2.0 error codes of the socket API (docs/socket-api.md) and the exception a method
// handler throws to answer with one of them. Anything else a handler throws becomes -32603.

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <string_view>

namespace fibrecell::api {

namespace errc {
// JSON-RPC 2.0 standard codes.
inline constexpr int parse_error = -32700;       // the line is not JSON
inline constexpr int invalid_request = -32600;   // JSON, but not a JSON-RPC 2.0 request
inline constexpr int method_not_found = -32601;  // no such method
inline constexpr int invalid_params = -32602;    // params missing, of the wrong type or range
inline constexpr int internal_error = -32603;    // a handler failed unexpectedly
// fibrecell application codes (server-defined range -32000..-32099).
inline constexpr int unauthorized = -32001;  // TCP without (or with a wrong) server.auth token
inline constexpr int not_found = -32002;     // no such job (or other named object)
inline constexpr int conflict = -32003;      // the call does not fit the job's/cell's state
inline constexpr int too_large = -32004;     // request line above api.max_request_bytes, or a
                                             // batch's answers above api.max_client_queue_bytes
inline constexpr int unavailable = -32005;   // the service cannot take it now (busy, draining)
}  // namespace errc

// "parse_error", "conflict", ... for a code; "error" for codes outside the table.
std::string_view error_name(int code);

class ApiError : public std::runtime_error {
  public:
    ApiError(int code, const std::string& message, nlohmann::json data = nullptr);

    int code() const { return code_; }
    const nlohmann::json& data() const { return data_; }  // null when there is none

    static ApiError invalid_params(const std::string& message);
    static ApiError unauthorized(const std::string& message);
    static ApiError not_found(const std::string& message);
    static ApiError conflict(const std::string& message);
    static ApiError unavailable(const std::string& message);
    static ApiError internal(const std::string& message);

  private:
    int code_;
    nlohmann::json data_;
};

}  // namespace fibrecell::api
