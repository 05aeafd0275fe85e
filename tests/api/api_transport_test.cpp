// The socket API's transports on real sockets: the Unix socket file (mode, group, stale and live
// sockets), the client's one-line errors, TCP with its token, and the client limit.
#include "api_server_fixture.hpp"
#include "tests/support/eventually.hpp"

#include <grp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

using namespace fibrecell::api;
using nlohmann::json;
using namespace std::chrono_literals;
using fibrecell::test::eventually;

namespace {

const std::string kTcpToken = "s3cret-token-0123456789";

std::string client_error(const ApiEndpoint& endpoint) {
    try {
        ApiClient::connect(endpoint);
    } catch (const ApiClientError& e) {
        return e.what();
    }
    return "";
}

class ApiTransportTest : public fibrecell::test::ApiServerTest {
  protected:
    ApiTransportTest() : ApiServerTest("api-tr") {
        config_.tcp.token = kTcpToken;
        config_.tcp.port = 0;  // ephemeral
    }
    void add_methods(ApiServer& server) override {
        server.add_method("whoami", [](const json&, const CallContext& ctx) {
            return json{{"tcp", ctx.transport == Transport::tcp}, {"peer", ctx.peer}};
        });
        server.add_method("halt", [](const json&, const CallContext&) { return json{{"halted", true}}; });
        server.add_control_method("halt");  // as the service marks pause, abort, estop
    }
    ApiEndpoint tcp(const std::string& token) const {
        return {.host = "127.0.0.1", .port = server_->tcp_port(), .token = token};
    }
};

// A socket file nobody listens on, as a crashed service leaves behind.
void make_stale_socket(const std::string& path) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strcpy(addr.sun_path, path.c_str());
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    ::close(fd);
}

}  // namespace

TEST_F(ApiTransportTest, SocketFileGetsTheConfiguredModeAndGroup) {
    config_.socket_mode = 0640;
    config_.socket_group = "65534";
    start();
    struct stat st {};
    ASSERT_EQ(::lstat(config_.socket_path.c_str(), &st), 0);
    EXPECT_TRUE(S_ISSOCK(st.st_mode));
    EXPECT_EQ(st.st_mode & 07777, 0640u);
    EXPECT_EQ(st.st_gid, 65534u);
    auto c = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(c.call("whoami")["tcp"], false);
    EXPECT_NE(c.call("whoami")["peer"].get<std::string>().find("unix uid="), std::string::npos);
}

TEST_F(ApiTransportTest, StaleSocketFromADeadProcessIsReplaced) {
    make_stale_socket(config_.socket_path);
    EXPECT_EQ(client_error({.socket_path = config_.socket_path}),
              "fibrecelld is not running (stale socket at " + config_.socket_path + ")");
    start();
    auto c = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(c.call("echo", {{"x", 1}}), (json{{"x", 1}}));
}

TEST_F(ApiTransportTest, LiveSocketIsRefusedAndKeepsServing) {
    start();
    boost::asio::io_context other_io;
    ApiServer second(other_io, config_);
    try {
        second.start();
        FAIL() << "a second server started on a live socket";
    } catch (const ApiStartError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "another fibrecelld is listening on " + config_.socket_path);
    }
    auto c = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(c.call("echo", {{"still", 1}}), (json{{"still", 1}}));
}

TEST_F(ApiTransportTest, AFileThatIsNotASocketIsLeftAlone) {
    std::ofstream(config_.socket_path) << "precious\n";
    try {
        start();
        FAIL() << "started over a regular file";
    } catch (const ApiStartError& e) {
        EXPECT_EQ(
            std::string(e.what()),
            config_.socket_path + " exists and is not a socket; remove it or choose another path");
    }
    std::ifstream in(config_.socket_path);
    std::string text;
    std::getline(in, text);
    EXPECT_EQ(text, "precious");
}

TEST_F(ApiTransportTest, MissingDirectoryIsAClearStartError) {
    config_.socket_path = (dir_ / "nope" / "api.sock").string();
    try {
        start();
        FAIL() << "started without a directory";
    } catch (const ApiStartError& e) {
        EXPECT_EQ(std::string(e.what()), "cannot create socket " + config_.socket_path +
                                             ": directory " + (dir_ / "nope").string() +
                                             " does not exist");
    }
}

TEST_F(ApiTransportTest, SocketFileIsRemovedOnStopUnlessReplaced) {
    start();
    stop_io();
    server_.reset();
    EXPECT_FALSE(std::filesystem::exists(config_.socket_path));
    // A successor's socket at the same path survives our late shutdown.
    start(false);
    std::filesystem::remove(config_.socket_path);
    make_stale_socket(config_.socket_path);
    server_.reset();
    EXPECT_TRUE(std::filesystem::exists(config_.socket_path));
}

TEST_F(ApiTransportTest, ClientSaysWhenTheServiceIsNotRunning) {
    EXPECT_EQ(client_error({.socket_path = config_.socket_path}),
              "fibrecelld is not running (no socket at " + config_.socket_path + ")");
    EXPECT_EQ(
        client_error({.socket_path = (dir_ / "nodir" / "x.sock").string()}),
        "fibrecelld is not running (no socket at " + (dir_ / "nodir" / "x.sock").string() + ")");
    EXPECT_EQ(client_error({.host = "127.0.0.1", .port = 1, .token = kTcpToken}),
              "fibrecelld is not listening on 127.0.0.1:1");
}

TEST_F(ApiTransportTest, ClientSaysPermissionDenied) {
    // Root passes every mode check, so the client runs in a child as nobody; otherwise mode 0
    // shuts out even the owner. The io thread is not started: fork() sees one thread, and the
    // kernel decides before any accept.
    const bool root = ::geteuid() == 0;
    config_.socket_mode = root ? 0600 : 0;
    std::filesystem::permissions(dir_.path(), std::filesystem::perms(0711));  // searchable for nobody
    start(false);
    const std::string expected = "permission denied on " + config_.socket_path;
    if (!root) {
        EXPECT_EQ(client_error({.socket_path = config_.socket_path}), expected);
        return;
    }
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        if (::setgroups(0, nullptr) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0) _exit(3);
        _exit(client_error({.socket_path = config_.socket_path}) == expected ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: another message, 3: could not become nobody";
}

TEST_F(ApiTransportTest, TcpWithTheRightTokenWorks) {
    config_.tcp.enabled = true;
    start();
    ASSERT_NE(server_->tcp_port(), 0);
    auto c = ApiClient::connect(tcp(kTcpToken));
    const json who = c.call("whoami");
    EXPECT_EQ(who["tcp"], true);
    EXPECT_NE(who["peer"].get<std::string>().find("tcp 127.0.0.1:"), std::string::npos);
    EXPECT_EQ(c.call("echo", {{"x", 2}}), (json{{"x", 2}}));
}

TEST_F(ApiTransportTest, TcpWithoutTokenIsUnauthorizedUntilAuth) {
    config_.tcp.enabled = true;
    start();
    auto c = ApiClient::connect(tcp(""));  // connects, does not authenticate
    try {
        c.call("echo");
        FAIL() << "answered without a token";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::unauthorized);
        EXPECT_STREQ(e.what(),
                     "unauthorized: the first call on a TCP connection must be server.auth "
                     "{\"token\": ...}");
    }
    try {
        c.call("subscribe");
        FAIL() << "subscribed without a token";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::unauthorized);
    }
    EXPECT_EQ(c.call("server.auth", {{"token", kTcpToken}}), (json{{"authenticated", true}}));
    EXPECT_EQ(c.call("echo", {{"x", 3}}), (json{{"x", 3}}));
}

// Guessing the token is bounded by the server, not by the number of connections: beyond
// api.tcp.auth_attempts_per_s the token is not even checked.
TEST_F(ApiTransportTest, WrongTokensAreCheckedAFewTimesASecondAtMost) {
    config_.tcp.enabled = true;
    config_.tcp.auth_attempts_per_s = 3;
    start();
    int wrong = 0, not_checked = 0;
    for (int i = 0; i < 20; ++i) {
        try {
            ApiClient::connect(tcp("wrong-token-wrong-token"));
        } catch (const ApiCallError& e) {
            if (e.code() == errc::unauthorized) ++wrong;
            if (e.code() == errc::unavailable) {
                ++not_checked;
                EXPECT_STREQ(e.what(), "unavailable: more than 3 server.auth attempts a second "
                                       "(api.tcp.auth_attempts_per_s); try again shortly");
            }
        }
    }
    EXPECT_EQ(wrong + not_checked, 20);
    EXPECT_LE(wrong, 3 + 3);  // the burst, and what a slow machine's seconds refill
    EXPECT_GE(not_checked, 10);
    // Once the budget has refilled, the right token gets in.
    EXPECT_TRUE(eventually([&] {
        try {
            ApiClient::connect(tcp(kTcpToken));
            return true;
        } catch (const ApiCallError&) {
            return false;
        }
    }, 10s, 200ms));
}

TEST_F(ApiTransportTest, TcpWithAWrongTokenIsRefusedAndClosed) {
    config_.tcp.enabled = true;
    start();
    try {
        ApiClient::connect(tcp("wrong-token-wrong-token"));
        FAIL() << "a wrong token was accepted";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), -32001);
        EXPECT_STREQ(e.what(), "unauthorized: wrong token");
    }
    auto c = ApiClient::connect(tcp(""));
    c.send_line(R"({"jsonrpc":"2.0","id":1,"method":"server.auth","params":{"token":"x"}})"
                "\n"
                R"({"jsonrpc":"2.0","id":2,"method":"echo"})");
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m);
    EXPECT_EQ((*m)["error"]["code"], errc::unauthorized);
    EXPECT_TRUE(c.wait_closed(5s));  // the pipelined call after it was never run
    EXPECT_EQ(server_->stats().auth_failures, 2u);
}

TEST_F(ApiTransportTest, ABatchOfGuessesGetsOneTryToo) {
    // A batch is one message: its elements must not each get the try a connection gets.
    config_.tcp.enabled = true;
    start();
    auto c = ApiClient::connect(tcp(""));
    std::string batch = "[";
    for (int i = 0; i < 50; ++i)
        batch += R"({"jsonrpc":"2.0","id":)" + std::to_string(i) +
                 R"(,"method":"server.auth","params":{"token":"guess-)" + std::to_string(i) +
                 R"("}},)";
    batch += R"({"jsonrpc":"2.0","id":50,"method":"server.auth","params":{"token":")" +
             std::string(kTcpToken) + R"("}},)";
    batch += R"({"jsonrpc":"2.0","id":51,"method":"whoami"}])";
    c.send_line(batch);
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m && m->is_array()) << (m ? m->dump() : "no answer");
    ASSERT_EQ(m->size(), 52u);
    const auto error_of = [](const json& answer) { return answer.value("error", json::object()); };
    for (const json& answer : *m)
        EXPECT_EQ(error_of(answer).value("code", 0), errc::unauthorized) << answer.dump();
    EXPECT_EQ(error_of((*m)[50]).value("message", ""),
              "unauthorized: this connection already gave a wrong token; reconnect");
    EXPECT_TRUE(c.wait_closed(5s));
    EXPECT_EQ(server_->stats().auth_failures, 1u);  // the first guess; the others never compared
}

TEST_F(ApiTransportTest, TcpConnectionThatNeverAuthenticatesIsClosed) {
    config_.tcp.enabled = true;
    config_.tcp.auth_timeout = 100ms;
    start();
    auto c = ApiClient::connect(tcp(""));
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m);
    EXPECT_EQ((*m)["error"]["code"], errc::unauthorized);
    EXPECT_EQ((*m)["error"]["message"], "unauthorized: no server.auth within 100 ms");
    EXPECT_TRUE(c.wait_closed(5s));
}

TEST_F(ApiTransportTest, AReloadedTokenAppliesToNewConnections) {
    config_.tcp.enabled = true;
    start();
    auto before = ApiClient::connect(tcp(kTcpToken));
    ApiConfig reloaded = config_;
    reloaded.tcp.token = "another-token-0123456789";
    server_->update_limits(reloaded);
    EXPECT_EQ(before.call("echo", {{"x", 1}}), (json{{"x", 1}}));  // stays authenticated
    EXPECT_THROW(ApiClient::connect(tcp(kTcpToken)), ApiCallError);
    auto after = ApiClient::connect(tcp(reloaded.tcp.token));
    EXPECT_EQ(after.call("echo", {{"x", 2}}), (json{{"x", 2}}));
}

TEST_F(ApiTransportTest, StopClosesClientsAndRemovesTheSocket) {
    start();
    auto c = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(c.call("echo", {{"x", 1}}), (json{{"x", 1}}));
    server_->stop();
    EXPECT_TRUE(c.wait_closed(5s));
    EXPECT_FALSE(std::filesystem::exists(config_.socket_path));
    EXPECT_EQ(client_error({.socket_path = config_.socket_path}),
              "fibrecelld is not running (no socket at " + config_.socket_path + ")");
}

TEST_F(ApiTransportTest, AFullServerKeepsRoomForControlCallsAndMakesMoreByClosingTheIdlest) {
    config_.max_clients = 3;
    config_.reserved_control_clients = 2;
    start();
    std::vector<ApiClient> idle;  // they took every ordinary place, and do nothing
    for (int i = 0; i < 3; ++i) {
        idle.push_back(ApiClient::connect({.socket_path = config_.socket_path}));
        idle.back().call("echo");
    }
    auto operator_ = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(operator_.call("halt"), (json{{"halted", true}}));
    try {
        operator_.call("echo");
        FAIL() << "a connection in the reserve called an ordinary method";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::unavailable);
        EXPECT_STREQ(e.what(), "unavailable: fibrecelld serves at most 3 clients at once "
                               "(api.max_clients); this connection may only call halt");
    }
    auto second = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(second.call("halt"), (json{{"halted", true}}));
    // Max and reserve taken: the next one is let in, and the connection idle longest goes.
    auto beyond = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(beyond.call("halt"), (json{{"halted", true}}));
    const auto m = idle[0].read_message(10s);
    ASSERT_TRUE(m) << "the idlest connection was not told";
    EXPECT_EQ((*m)["error"]["code"], errc::unavailable);
    EXPECT_EQ((*m)["error"]["message"],
              "unavailable: closed for a newer connection: fibrecelld serves at most 5 clients at "
              "once (api.max_clients + api.reserved_control_clients); the one idle longest goes first");
    EXPECT_TRUE(idle[0].wait_closed(5s));
    EXPECT_EQ(idle[1].call("echo", {{"x", 1}}), (json{{"x", 1}}));  // the others are still served
    EXPECT_EQ(server_->stats().control_only, 3u);
    EXPECT_EQ(server_->stats().evicted, 1u);
    EXPECT_EQ(server_->stats().refused_full, 0u);
}

TEST_F(ApiTransportTest, TcpConnectionsThatNeverAuthenticateHaveASmallLimitOfTheirOwn) {
    config_.tcp.enabled = true;
    config_.tcp.max_unauthenticated = 2;
    start();
    auto first = ApiClient::connect(tcp(""));
    auto second = ApiClient::connect(tcp(""));
    // Each asks something (unauthorized), the first last: the second has been idle longer.
    EXPECT_THROW(second.call("echo"), ApiCallError);
    EXPECT_THROW(first.call("echo"), ApiCallError);
    auto third = ApiClient::connect(tcp(""));
    // The oldest of those still to authenticate made room for the third.
    const auto m = second.read_message(10s);
    ASSERT_TRUE(m);
    EXPECT_EQ((*m)["error"]["message"],
              "unavailable: closed for a newer connection: at most 2 connections may wait for "
              "server.auth (api.tcp.max_unauthenticated)");
    EXPECT_EQ(third.call("server.auth", {{"token", kTcpToken}}), (json{{"authenticated", true}}));
    // The Unix socket is not touched by them.
    auto local = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(local.call("echo", {{"x", 1}}), (json{{"x", 1}}));
    EXPECT_EQ(server_->stats().evicted, 1u);
}

TEST_F(ApiTransportTest, AnIdleConnectionIsClosedASubscriberIsNot) {
    config_.idle_timeout = 300ms;
    start();
    auto idle = ApiClient::connect({.socket_path = config_.socket_path});
    auto subscriber = ApiClient::connect({.socket_path = config_.socket_path});
    subscriber.call("subscribe", {{"topics", {"cell"}}});
    idle.call("echo");
    const auto m = idle.read_message(10s);
    ASSERT_TRUE(m) << "the idle connection was not told";
    EXPECT_EQ((*m)["error"]["code"], errc::unavailable);
    EXPECT_EQ((*m)["error"]["message"],
              "unavailable: no request for 300 ms (api.idle_timeout_s); closing the connection");
    EXPECT_TRUE(idle.wait_closed(5s));
    EXPECT_EQ(server_->stats().closed_idle, 1u);
    // The subscriber, silent as long, is still served.
    EXPECT_EQ(subscriber.call("echo", {{"x", 1}}), (json{{"x", 1}}));
}

TEST_F(ApiTransportTest, AControlConnectionIdlesOutSooner) {
    config_.max_clients = 1;
    config_.control_idle_timeout = 200ms;
    start();
    auto ordinary = ApiClient::connect({.socket_path = config_.socket_path});
    ordinary.call("echo");
    auto control = ApiClient::connect({.socket_path = config_.socket_path});
    control.call("halt");
    EXPECT_TRUE(control.wait_closed(10s));  // its place is free again for the next operator
    EXPECT_EQ(ordinary.call("echo", {{"x", 1}}), (json{{"x", 1}}));  // 300 s: still open
}

TEST_F(ApiTransportTest, TcpIsOffByDefault) {
    start();
    EXPECT_EQ(server_->tcp_port(), 0);
}

TEST_F(ApiTransportTest, ANewClientAtTheLimitIsLetInAndOnlyRefusedWhenEveryOtherIsBusy) {
    config_.max_clients = 1;
    config_.reserved_control_clients = 0;
    start();
    auto first = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(first.call("echo", {{"n", 1}}), (json{{"n", 1}}));
    auto second = ApiClient::connect({.socket_path = config_.socket_path});
    EXPECT_EQ(second.call("echo", {{"n", 2}}), (json{{"n", 2}}));
    EXPECT_TRUE(first.wait_closed(5s));  // it made room
    EXPECT_EQ(server_->stats().evicted, 1u);
    EXPECT_EQ(server_->stats().refused_full, 0u);
}
