#pragma once
// JSON-RPC 2.0 message shapes (https://www.jsonrpc.org/specification), independent of sockets:
// checking one request object and building responses, notifications and wire lines.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::api {

struct RpcRequest {
    std::string method;
    nlohmann::json params;      // {} when absent, else the object or array given
    nlohmann::json id;          // string, number or null; null also for notifications
    bool notification = false;  // no "id" member: nothing is answered
};

// One element of a message (a whole single message or one entry of a batch): either a request,
// or the invalid-request response to send instead (with the id when one could be read).
struct CheckedRequest {
    std::optional<RpcRequest> request;
    nlohmann::json error;  // an error response object when !request
};
// Takes the element apart (params are moved, not copied: they may hold megabytes of job files).
CheckedRequest check_request(nlohmann::json&& element);

// Deepest nesting of arrays/objects in JSON text, not counting brackets inside strings. Checked
// before parsing: copying and destroying very deep values recurses.
std::size_t nesting_depth(std::string_view text);
inline constexpr std::size_t kMaxNestingDepth = 128;

// One request line (not blank) read: the message, or the error response to send instead when it
// is nested deeper than kMaxNestingDepth (invalid_request) or is not JSON this service can hold
// (parse_error: bad syntax, invalid UTF-8, a number no double holds such as 1e400).
struct ParsedLine {
    nlohmann::json message;
    nlohmann::json error;  // an error response object when the line was refused, else null
};
ParsedLine parse_line(std::string_view line);

nlohmann::json result_response(const nlohmann::json& id, nlohmann::json result);
nlohmann::json error_response(const nlohmann::json& id, int code, const std::string& message,
                              const nlohmann::json& data = nullptr);
nlohmann::json notification_message(const std::string& method, nlohmann::json params);
nlohmann::json request_message(const nlohmann::json& id, const std::string& method,
                               nlohmann::json params);

// Compact JSON plus '\n'; invalid UTF-8 in strings is replaced rather than thrown on.
std::string to_line(const nlohmann::json& message);

}  // namespace fibrecell::api
