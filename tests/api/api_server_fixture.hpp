#pragma once
// What the socket API's tests share: an ApiServer on a Unix socket in a temporary folder, its
// io_context on a thread of its own, and ApiClient connections to it. A test sets config_, then
// start(); a fixture adds its own methods in add_methods() (every server has "echo").

#include "daemon/api/api_client.hpp"
#include "daemon/api/api_server.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>

#include <chrono>
#include <memory>
#include <string_view>
#include <thread>

namespace fibrecell::test {

class ApiServerTest : public ::testing::Test {
  protected:
    explicit ApiServerTest(std::string_view prefix) : dir_(prefix) {
        config_.socket_path = (dir_ / "api.sock").string();
    }
    void TearDown() override {
        stop_io();
        server_.reset();
    }

    // The server with config_ and its methods, bound; its io thread runs unless told not to.
    void start(bool run_io = true) {
        server_ = std::make_unique<api::ApiServer>(io_, config_);
        server_->add_method("echo", [](const nlohmann::json& params, const api::CallContext&) {
            return params;
        });
        add_methods(*server_);
        server_->start();
        if (run_io) io_thread_ = std::thread([this] { io_.run(); });
    }
    virtual void add_methods(api::ApiServer&) {}
    void stop_io() {
        work_.reset();
        io_.stop();
        if (io_thread_.joinable()) io_thread_.join();
    }
    api::ApiClient client() const {
        return api::ApiClient::connect({.socket_path = config_.socket_path});
    }

    TempDir dir_;
    api::ApiConfig config_;
    boost::asio::io_context io_;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_ =
        boost::asio::make_work_guard(io_);
    std::unique_ptr<api::ApiServer> server_;
    std::thread io_thread_;
};

// The JSON-RPC error code a call is answered with; 0 when it succeeds.
inline int call_error_code(api::ApiClient& c, const std::string& method,
                           nlohmann::json params = nlohmann::json::object(),
                           std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    try {
        c.call(method, std::move(params), timeout);
    } catch (const api::ApiCallError& e) {
        return e.code();
    }
    return 0;
}

}  // namespace fibrecell::test
