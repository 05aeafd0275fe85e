// The dashboard's HTTP listener on real loopback TCP, against a real ApiServer: pages without a
// login but nothing else, the login and its limit, and the API over a WebSocket answering as the
// socket API does (the same dispatcher, errors and events).
#include "daemon/api/api_server.hpp"
#include "daemon/http/http_server.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <sys/socket.h>

#include <fstream>
#include <optional>
#include <thread>

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace bhttp = beast::http;
namespace websocket = beast::websocket;
using asio::ip::tcp;
using nlohmann::json;
using namespace fibrecell;
using namespace std::chrono_literals;

namespace {

const std::string kToken = "dashboard-token-0123456789";
using Response = bhttp::response<bhttp::string_body>;

// A blocking socket that gives up after five seconds instead of hanging the test.
void time_out_reads(tcp::socket& s) {
    timeval tv{5, 0};
    ::setsockopt(s.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
}

class HttpServerTest : public ::testing::Test {
  protected:
    HttpServerTest() : dir_("http") {
        std::filesystem::create_directories(dir_ / "web/js");
        std::filesystem::create_directories(dir_ / "plans/7/preview");
        std::ofstream(dir_ / "web/index.html") << "<!doctype html><title>fibrecell</title>";
        std::ofstream(dir_ / "web/js/app.js") << "export {};";
        std::ofstream(dir_ / "web/.secret") << "hidden";
        std::ofstream(dir_ / "outside.txt") << "not a page";
        std::filesystem::create_symlink(dir_ / "outside.txt", dir_ / "web/link.txt");
        std::ofstream(dir_ / "plans/7/report.json") << R"({"layers": {"pla": 2}})";
        std::ofstream(dir_ / "plans/7/preview/layer_0000.svg") << "<svg/>";
        config_.socket_path = (dir_ / "api.sock").string();
        config_.http.enabled = true;
        config_.http.port = 0;
        config_.http.token = kToken;
        config_.http.web_root = (dir_ / "web").string();
        config_.http.login_failures_per_minute = 3;
        config_.max_request_bytes = 4096;
    }

    void SetUp() override {
        api_ = std::make_unique<api::ApiServer>(io_, config_);
        api_->add_method("echo", [](const json& params, const api::CallContext& ctx) {
            return json{{"params", params},
                        {"websocket", ctx.transport == api::Transport::websocket},
                        {"peer", ctx.peer}};
        });
        api_->start();
        http_ = std::make_unique<http::HttpServer>(io_, config_, *api_);
        http_->add_file_route("/api/jobs/", [this](std::string_view key) -> std::optional<std::filesystem::path> {
            if (key != "7") return std::nullopt;
            return dir_ / "plans/7";
        });
        http_->start();
        io_thread_ = std::thread([this] { io_.run(); });
    }

    void TearDown() override {
        work_.reset();
        io_.stop();
        io_thread_.join();
        http_.reset();
        api_.reset();
    }

    tcp::socket connect() {
        tcp::socket s(client_io_);
        s.connect({asio::ip::make_address("127.0.0.1"), http_->port()});
        time_out_reads(s);
        return s;
    }

    Response request(bhttp::verb verb, const std::string& target, const std::string& body = "",
                     const std::string& cookie = "") {
        tcp::socket s = connect();
        bhttp::request<bhttp::string_body> req{verb, target, 11};
        req.set(bhttp::field::host, "127.0.0.1:" + std::to_string(http_->port()));
        if (!cookie.empty()) req.set(bhttp::field::cookie, cookie);
        if (!body.empty()) {
            req.set(bhttp::field::content_type, "application/json");
            req.body() = body;
        }
        req.prepare_payload();
        bhttp::write(s, req);
        beast::flat_buffer buffer;
        Response res;
        bhttp::read(s, buffer, res);
        return res;
    }

    // The session cookie ("fibrecell_session=...") of a right login.
    std::string log_in() {
        const Response res = request(bhttp::verb::post, "/api/login", json{{"token", kToken}}.dump());
        EXPECT_EQ(res.result(), bhttp::status::ok) << res.body();
        const std::string set = std::string(res[bhttp::field::set_cookie]);
        return set.substr(0, set.find(';'));
    }

    using Ws = websocket::stream<tcp::socket>;
    // A WebSocket to /api/ws, or null when the upgrade is refused.
    std::unique_ptr<Ws> open_ws(const std::string& cookie, const std::string& origin = "") {
        auto ws = std::make_unique<Ws>(connect());
        ws->set_option(websocket::stream_base::decorator([&](websocket::request_type& req) {
            if (!cookie.empty()) req.set(bhttp::field::cookie, cookie);
            if (!origin.empty()) req.set(bhttp::field::origin, origin);
        }));
        beast::error_code ec;
        ws->handshake("127.0.0.1:" + std::to_string(http_->port()), "/api/ws", ec);
        return ec ? nullptr : std::move(ws);
    }

    // The HTTP status an upgrade request to /api/ws is answered with.
    bhttp::status upgrade_status(const std::string& cookie, const std::string& origin = "") {
        tcp::socket s = connect();
        bhttp::request<bhttp::empty_body> req{bhttp::verb::get, "/api/ws", 11};
        req.set(bhttp::field::host, "127.0.0.1:" + std::to_string(http_->port()));
        req.set(bhttp::field::upgrade, "websocket");
        req.set(bhttp::field::connection, "Upgrade");
        req.set(bhttp::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
        req.set(bhttp::field::sec_websocket_version, "13");
        if (!cookie.empty()) req.set(bhttp::field::cookie, cookie);
        if (!origin.empty()) req.set(bhttp::field::origin, origin);
        bhttp::write(s, req);
        beast::flat_buffer buffer;
        Response res;
        bhttp::read(s, buffer, res);
        return res.result();
    }

    static json read_json(Ws& ws) {
        beast::flat_buffer buffer;
        ws.read(buffer);
        return json::parse(beast::buffers_to_string(buffer.data()));
    }

    test::TempDir dir_;
    api::ApiConfig config_;
    asio::io_context io_;
    asio::executor_work_guard<asio::io_context::executor_type> work_ = asio::make_work_guard(io_);
    std::unique_ptr<api::ApiServer> api_;
    std::unique_ptr<http::HttpServer> http_;
    std::thread io_thread_;
    asio::io_context client_io_;
};

TEST_F(HttpServerTest, PagesNeedNoLoginButNothingElseIsServed) {
    Response index = request(bhttp::verb::get, "/");
    EXPECT_EQ(index.result(), bhttp::status::ok);
    EXPECT_NE(index.body().find("<title>fibrecell</title>"), std::string::npos);
    EXPECT_EQ(index[bhttp::field::content_type], "text/html; charset=utf-8");
    EXPECT_NE(std::string(index["Content-Security-Policy"]).find("default-src 'self'"), std::string::npos);
    EXPECT_EQ(index["X-Frame-Options"], "DENY");
    Response script = request(bhttp::verb::get, "/js/app.js?v=2");
    EXPECT_EQ(script.result(), bhttp::status::ok);
    EXPECT_EQ(script[bhttp::field::content_type], "text/javascript; charset=utf-8");

    for (const char* target : {"/.secret", "/../outside.txt", "/js/../../outside.txt", "/link.txt",
                               "/js/", "/js", "/%2e%2e/outside.txt", "//etc/passwd", "/missing.html"}) {
        const Response res = request(bhttp::verb::get, target);
        EXPECT_EQ(res.result(), bhttp::status::not_found) << target << ": " << res.body();
        EXPECT_EQ(res.body().find("hidden"), std::string::npos);
        EXPECT_EQ(res.body().find("not a page"), std::string::npos);
    }
    EXPECT_EQ(request(bhttp::verb::post, "/index.html", "{}").result(),
              bhttp::status::method_not_allowed);
}

TEST_F(HttpServerTest, ALoginSetsAStrictHttpOnlyCookieAndAWrongTokenIsRefused) {
    EXPECT_EQ(json::parse(request(bhttp::verb::get, "/api/session").body())["authenticated"], false);

    const Response wrong = request(bhttp::verb::post, "/api/login", json{{"token", "guess"}}.dump());
    EXPECT_EQ(wrong.result(), bhttp::status::unauthorized);
    EXPECT_EQ(json::parse(wrong.body())["error"], "wrong token");
    EXPECT_EQ(wrong.count(bhttp::field::set_cookie), 0u);
    EXPECT_EQ(request(bhttp::verb::post, "/api/login", "not json").result(), bhttp::status::bad_request);

    const Response right = request(bhttp::verb::post, "/api/login", json{{"token", kToken}}.dump());
    ASSERT_EQ(right.result(), bhttp::status::ok);
    const std::string set = std::string(right[bhttp::field::set_cookie]);
    EXPECT_NE(set.find("HttpOnly"), std::string::npos) << set;
    EXPECT_NE(set.find("SameSite=Strict"), std::string::npos) << set;
    EXPECT_NE(set.find("Path=/"), std::string::npos) << set;
    const std::string cookie = set.substr(0, set.find(';'));
    EXPECT_EQ(json::parse(request(bhttp::verb::get, "/api/session", "", cookie).body())["authenticated"], true);
    EXPECT_EQ(json::parse(request(bhttp::verb::get, "/api/session", "", cookie + "0").body())["authenticated"],
              false);

    request(bhttp::verb::post, "/api/logout", "", cookie);
    EXPECT_EQ(json::parse(request(bhttp::verb::get, "/api/session", "", cookie).body())["authenticated"], false);
    EXPECT_EQ(http_->stats().logins, 1u);
    EXPECT_EQ(http_->stats().login_failures, 1u);
}

TEST_F(HttpServerTest, TooManyWrongTokensHoldTheAddressBackEvenWithTheRightOne) {
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(request(bhttp::verb::post, "/api/login", json{{"token", "guess" + std::to_string(i)}}.dump())
                      .result(),
                  bhttp::status::unauthorized);
    const Response held = request(bhttp::verb::post, "/api/login", json{{"token", kToken}}.dump());
    EXPECT_EQ(held.result(), bhttp::status::too_many_requests) << held.body();
    EXPECT_NE(json::parse(held.body())["error"].get<std::string>().find("too many wrong tokens"),
              std::string::npos);
    const int retry = std::stoi(std::string(held[bhttp::field::retry_after]));
    EXPECT_GT(retry, 0);
    EXPECT_LE(retry, 60);
    EXPECT_EQ(held.count(bhttp::field::set_cookie), 0u);
    EXPECT_EQ(http_->stats().login_throttled, 1u);
}

TEST_F(HttpServerTest, TheWebSocketNeedsALoginAndAPageOfOurOwn) {
    EXPECT_EQ(upgrade_status(""), bhttp::status::unauthorized);
    EXPECT_EQ(upgrade_status("fibrecell_session=forged"), bhttp::status::unauthorized);
    EXPECT_EQ(open_ws(""), nullptr);

    const std::string cookie = log_in();
    EXPECT_EQ(upgrade_status(cookie, "http://evil.example"), bhttp::status::forbidden);
    const std::string own = "http://127.0.0.1:" + std::to_string(http_->port());
    EXPECT_EQ(upgrade_status(cookie, own), bhttp::status::switching_protocols);
    EXPECT_NE(open_ws(cookie, own), nullptr);
    EXPECT_EQ(http_->stats().unauthorized, 4u);
    EXPECT_EQ(http_->stats().websockets, 2u);
}

TEST_F(HttpServerTest, TheWebSocketSpeaksTheSocketApi) {
    auto ws = open_ws(log_in());
    ASSERT_NE(ws, nullptr);
    ws->text(true);
    ws->write(asio::buffer(json{{"jsonrpc", "2.0"}, {"id", 1}, {"method", "echo"}, {"params", {{"a", 1}}}}.dump()));
    const json answer = read_json(*ws);
    EXPECT_EQ(answer["id"], 1);
    EXPECT_EQ(answer["result"]["params"]["a"], 1);
    EXPECT_EQ(answer["result"]["websocket"], true);
    EXPECT_EQ(answer["result"]["peer"].get<std::string>().rfind("websocket 127.0.0.1:", 0), 0u);

    // A pretty-printed request (line breaks between tokens) means the same.
    ws->write(asio::buffer(std::string("{\n \"jsonrpc\": \"2.0\",\n \"id\": 2,\n \"method\": \"echo\"\n}")));
    EXPECT_EQ(read_json(*ws)["id"], 2);

    // The socket API's own errors.
    ws->write(asio::buffer(std::string("{not json")));
    EXPECT_EQ(read_json(*ws)["error"]["code"], -32700);
    ws->write(asio::buffer(json{{"jsonrpc", "2.0"}, {"id", 3}, {"method", "no.such"}}.dump()));
    EXPECT_EQ(read_json(*ws)["error"]["code"], -32601);

    // Events: subscribed, published, delivered.
    ws->write(asio::buffer(json{{"jsonrpc", "2.0"}, {"id", 4}, {"method", "subscribe"},
                                {"params", {{"topics", {"cell"}}}}}.dump()));
    EXPECT_EQ(read_json(*ws)["id"], 4);
    api_->publish({.topic = "cell", .method = "notify.cell_status", .params = {{"n", 7}}});
    const json event = read_json(*ws);
    EXPECT_EQ(event["method"], "notify.cell_status");
    EXPECT_EQ(event["params"]["n"], 7);
}

TEST_F(HttpServerTest, ALogoutOrANewTokenEndsTheWebSocketsOfThatLogin) {
    const std::string cookie = log_in();
    auto ws = open_ws(cookie);
    ASSERT_NE(ws, nullptr);
    ws->write(asio::buffer(json{{"jsonrpc", "2.0"}, {"id", 1}, {"method", "subscribe"}}.dump()));
    EXPECT_EQ(read_json(*ws)["id"], 1);
    request(bhttp::verb::post, "/api/logout", "", cookie);
    // A watcher's next event finds the login gone: the WebSocket closes instead.
    api_->publish({.topic = "cell", .method = "notify.cell_status", .params = {{"n", 1}}});
    beast::flat_buffer buffer;
    beast::error_code ec;
    ws->read(buffer, ec);
    EXPECT_EQ(ec, websocket::error::closed) << ec.message() << " " << beast::buffers_to_string(buffer.data());
    EXPECT_EQ(ws->reason().code, websocket::close_code::policy_error);

    // A new token (a reload) ends every login, and a request on an open WebSocket finds it so.
    auto other = open_ws(log_in());
    ASSERT_NE(other, nullptr);
    config_.http.token = "another-token-0123456789";
    http_->update(config_);
    other->write(asio::buffer(json{{"jsonrpc", "2.0"}, {"id", 2}, {"method", "echo"}}.dump()));
    other->read(buffer, ec);
    EXPECT_TRUE(ec) << "an answer came after the token changed: " << beast::buffers_to_string(buffer.data());
}

TEST_F(HttpServerTest, ARequestOverTheApisLimitGetsTheApisAnswer) {
    auto ws = open_ws(log_in());
    ASSERT_NE(ws, nullptr);
    const std::string big = json{{"jsonrpc", "2.0"}, {"id", 1}, {"method", "echo"},
                                 {"params", {{"pad", std::string(8000, 'x')}}}}.dump();
    ws->write(asio::buffer(big));
    const json answer = read_json(*ws);
    EXPECT_EQ(answer["error"]["code"], -32004);  // too_large, as on the socket
    EXPECT_NE(answer["error"]["message"].get<std::string>().find("api.max_request_bytes"), std::string::npos)
        << answer.dump();
    // The API closed that client: the WebSocket closes too.
    beast::flat_buffer buffer;
    beast::error_code ec;
    ws->read(buffer, ec);
    EXPECT_EQ(ec, websocket::error::closed) << ec.message();

    // Far over it (3 MiB), the same answer: the WebSocket has no limit of its own to close with.
    auto far = open_ws(log_in());
    ASSERT_NE(far, nullptr);
    far->write(asio::buffer(json{{"jsonrpc", "2.0"}, {"id", 2}, {"method", "echo"},
                                 {"params", {{"pad", std::string(3 << 20, 'x')}}}}.dump()));
    EXPECT_EQ(read_json(*far)["error"]["code"], -32004);
}

TEST_F(HttpServerTest, PlanFilesNeedTheLoginAndStayInTheirFolder) {
    EXPECT_EQ(request(bhttp::verb::get, "/api/jobs/7/report.json").result(), bhttp::status::unauthorized);
    const std::string cookie = log_in();
    const Response report = request(bhttp::verb::get, "/api/jobs/7/report.json", "", cookie);
    EXPECT_EQ(report.result(), bhttp::status::ok);
    EXPECT_EQ(json::parse(report.body())["layers"]["pla"], 2);
    const Response layer = request(bhttp::verb::get, "/api/jobs/7/preview/layer_0000.svg", "", cookie);
    EXPECT_EQ(layer[bhttp::field::content_type], "image/svg+xml");
    for (const char* target : {"/api/jobs/8/report.json", "/api/jobs/7/../7/report.json",
                               "/api/jobs/7/../../outside.txt", "/api/jobs/7", "/api/jobs/7/",
                               "/api/nothing"})
        EXPECT_EQ(request(bhttp::verb::get, target, "", cookie).result(), bhttp::status::not_found)
            << target;
}

TEST_F(HttpServerTest, AFullListenerClosesTheConnectionWaitingLongestForTheNewcomer) {
    config_.max_clients = 3;
    http_->update(config_);
    // Three clients each send half a request (headers without their end) and stop.
    std::vector<tcp::socket> half;
    for (int i = 0; i < 3; ++i) {
        half.push_back(connect());
        asio::write(half.back(), asio::buffer(std::string("GET /api/session HTTP/1.1\r\nHost: 127.0.0.1\r\n")));
        const auto deadline = std::chrono::steady_clock::now() + 10s;
        while (http_->stats().open < static_cast<std::uint64_t>(i + 1) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(1ms);
    }
    ASSERT_EQ(http_->stats().open, 3u);
    // The operator's request is answered: the one waiting longest made room for it.
    EXPECT_EQ(request(bhttp::verb::get, "/api/session").result(), bhttp::status::ok);
    char byte = 0;
    beast::error_code ec;
    half[0].read_some(asio::buffer(&byte, 1), ec);
    EXPECT_EQ(ec, asio::error::eof) << "the first half-sent request is closed: " << ec.message();
    EXPECT_EQ(http_->stats().refused_busy, 1u);
    // The later ones still wait, and their requests are answered once they end.
    asio::write(half[2], asio::buffer(std::string("\r\n")));
    beast::flat_buffer buffer;
    Response res;
    bhttp::read(half[2], buffer, res);
    EXPECT_EQ(res.result(), bhttp::status::ok);
}

}  // namespace
