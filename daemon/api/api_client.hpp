#pragma once
// A blocking client of the socket API for the CLI and tests: connect to the Unix socket or to
// host:port with a token, call methods with a timeout, receive notifications. Failures come as
// one clear line:
//   ApiClientError  the transport: "fibrecelld is not running (no socket at <path>)",
//                   "permission denied on <path>", "no answer to job.get within 10000 ms", ...
//   ApiCallError    the service answered with a JSON-RPC error (code, message, data).
//
//   auto client = ApiClient::connect({.socket_path = "/run/fibrecelld/api.sock"});
//   nlohmann::json jobs = client.call("job.list");
//   client.call("subscribe", {{"topics", {job_id}}});
//   while (auto n = client.next_notification(1s)) ...
//
// Not thread-safe: one thread uses a client at a time.

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace fibrecell::api {

class ApiClientError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class ApiCallError : public std::runtime_error {
  public:
    ApiCallError(int code, const std::string& message, nlohmann::json data = nullptr);
    int code() const { return code_; }
    const nlohmann::json& data() const { return data_; }

  private:
    int code_;
    nlohmann::json data_;
};

struct ApiEndpoint {
    std::string socket_path;  // used when host is empty
    std::string host;         // TCP when set
    std::uint16_t port = 7420;
    std::string token;  // sent with server.auth on TCP (empty: not sent)
};

struct ApiClientOptions {
    std::chrono::milliseconds connect_timeout{3000};
    std::chrono::milliseconds call_timeout{10000};  // default for call()
    std::size_t max_message_bytes = std::size_t{1} << 30;
};

struct ApiNotification {
    std::string method;
    nlohmann::json params;
};

class ApiClient {
  public:
    // Connects (and on TCP authenticates); throws ApiClientError or ApiCallError (wrong token).
    static ApiClient connect(const ApiEndpoint& endpoint, ApiClientOptions options = {});

    ApiClient(ApiClient&&) noexcept;
    ApiClient& operator=(ApiClient&&) noexcept;
    ~ApiClient();

    // Sends a request and waits for its answer; notifications arriving meanwhile are kept for
    // next_notification(). Throws ApiCallError when the service answers with an error (also
    // one addressed to no id: a refused or oversized request) and ApiClientError on transport
    // failures or timeout.
    nlohmann::json call(const std::string& method, nlohmann::json params = nlohmann::json::object(),
                        std::optional<std::chrono::milliseconds> timeout = std::nullopt);
    // A JSON-RPC notification: nothing is answered.
    void notify(const std::string& method, nlohmann::json params = nlohmann::json::object());

    // The next notification, or nullopt after `timeout`.
    std::optional<ApiNotification> next_notification(std::chrono::milliseconds timeout);

    // Raw access for tools and protocol tests: send any text (a '\n' is appended if missing), read
    // the next message of any kind (nullopt after timeout; notifications are not set aside).
    void send_line(std::string line);
    std::optional<nlohmann::json> read_message(std::chrono::milliseconds timeout);

    // Waits for the service to close the connection; true when it did within `timeout`.
    bool wait_closed(std::chrono::milliseconds timeout);

    const std::string& describe() const;  // "/run/fibrecelld/api.sock" or "host:port"

  private:
    struct Impl;
    explicit ApiClient(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::api
