// The RWS client against the simulator's RWS server over real loopback TCP (ephemeral ports):
// digest handshake, sessions, stale nonces, module upload/load with build errors, mastership,
// execution, PERS data, and the transport failures. Plus the digest arithmetic on RFC 2617's
// worked example.

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "drivers/abb/rws/digest.hpp"
#include "drivers/sim/rws/in_memory_controller.hpp"
#include "drivers/abb/rws/rws_client.hpp"
#include "drivers/sim/rws/rws_routes.hpp"
#include "drivers/sim/rws/rws_server.hpp"
#include "drivers/abb/rws/url.hpp"
#include "tests/support/eventually.hpp"

using namespace fibrecell::drivers::abb::rws;
using namespace fibrecell::drivers::sim::rws;  // the simulated controller's side
using namespace std::chrono_literals;
using fibrecell::test::eventually;

namespace {

const std::string good_module =
    "MODULE Good\n"
    "  PERS num nLayer := 0;\n"
    "  PERS string sJob := \"none\";\n"
    "  CONST num nPasses := 3;\n"
    "\n"
    "  PROC main()\n"
    "    nLayer := nLayer + 1;\n"
    "  ENDPROC\n"
    "ENDMODULE\n";

// Line 4 is not RAPID.
const std::string bad_module =
    "MODULE Bad\n"
    "  PERS num nCount := 0;\n"
    "  PROC Run()\n"
    "    nCount := * 2;\n"
    "  ENDPROC\n"
    "ENDMODULE\n";

bool has_module(const std::vector<ModuleInfo>& ms, const std::string& name) {
    return std::any_of(ms.begin(), ms.end(), [&](const ModuleInfo& m) { return m.name == name; });
}

// Runs `f`, expects an RwsError and returns it.
template <class F>
RwsError rws_error(F f) {
    try {
        f();
    } catch (const RwsError& e) {
        std::cout << "  RwsError[" << to_string(e.kind()) << "] " << e.what() << "\n";
        return e;
    }
    ADD_FAILURE() << "no RwsError thrown";
    return RwsError(RwsErrorKind::protocol, "none");
}

class RwsTest : public ::testing::Test {
  protected:
    void SetUp() override { start(); }

    void start(RwsServerConfig config = {}) {
        controller_ = std::make_shared<InMemoryController>();
        server_ = std::make_unique<RwsServer>(controller_, config);
    }

    RwsClientConfig client_config() const {
        RwsClientConfig c;
        c.host = "127.0.0.1";
        c.port = server_->port();
        c.connect_timeout = 1000ms;
        c.request_timeout = 2000ms;
        return c;
    }

    RwsClient& client() {
        if (!client_) client_ = std::make_unique<RwsClient>(client_config());
        return *client_;
    }

    std::string where() const { return "127.0.0.1:" + std::to_string(server_->port()); }

    void load_good() {
        client().request_mastership();
        client().upload_file("Good.mod", good_module);
        client().load_module("Good.mod");
    }

    std::shared_ptr<InMemoryController> controller_;
    std::unique_ptr<RwsServer> server_;
    std::unique_ptr<RwsClient> client_;
};

}  // namespace

// ---- Digest arithmetic -------------------------------------------------------------------------

TEST(Digest, Rfc2617WorkedExample) {
    DigestInput in;
    in.user = "Mufasa";
    in.realm = "testrealm@host.com";
    in.password = "Circle Of Life";
    in.method = "GET";
    in.uri = "/dir/index.html";
    in.nonce = "dcd98b7102dd2f0e8b11d0f600bfb0c093";
    in.nc = "00000001";
    in.cnonce = "0a4f113b";
    in.qop = "auth";
    EXPECT_EQ(digest_response(in), "6629fae49393a05397450978507c4ef1");
    EXPECT_EQ(md5_hex(""), "d41d8cd98f00b204e9800998ecf8427e");
    EXPECT_EQ(format_nc(1), "00000001");
    EXPECT_EQ(format_nc(255), "000000ff");
}

TEST(Digest, ParsesChallenges) {
    const auto c = parse_challenge(
        "Digest realm=\"testrealm@host.com\", qop=\"auth,auth-int\", "
        "nonce=\"dcd98b7102dd2f0e8b11d0f600bfb0c093\", "
        "opaque=\"5ccc069c403ebaf9f0171e9517f40e41\"");
    ASSERT_TRUE(c);
    EXPECT_EQ(c->realm, "testrealm@host.com");
    EXPECT_EQ(c->nonce, "dcd98b7102dd2f0e8b11d0f600bfb0c093");
    EXPECT_EQ(c->opaque, "5ccc069c403ebaf9f0171e9517f40e41");
    EXPECT_EQ(c->qop, (std::vector<std::string>{"auth", "auth-int"}));
    EXPECT_EQ(c->algorithm, "MD5");
    EXPECT_FALSE(c->stale);

    const auto rws = parse_challenge(
        "Digest realm=\"validusers@robapi.abb\", domain=\"/\", qop=\"auth\", nonce=\"a\\\"b\", "
        "algorithm=MD5, stale=TRUE");
    ASSERT_TRUE(rws);
    EXPECT_EQ(rws->nonce, "a\"b");
    EXPECT_TRUE(rws->stale);

    EXPECT_FALSE(parse_challenge("Basic realm=\"x\""));
    EXPECT_FALSE(parse_challenge("Digest realm=\"x\""));             // no nonce
    EXPECT_FALSE(parse_challenge("Digest realm=\"x, nonce=\"y\""));  // unterminated quote
}

TEST(Digest, ClientAndVerifierAgreeAndCountNc) {
    DigestVerifier verifier({"realm@test", "Default User", "robotics", 300s});
    DigestSession session("Default User", "robotics");
    session.accept(*parse_challenge(verifier.challenge(false).header));

    const std::string first = session.authorization("GET", "/rw/panel/ctrlstate?json=1");
    EXPECT_NE(first.find("nc=00000001"), std::string::npos) << first;
    EXPECT_EQ(verifier.verify(first, "GET", "/rw/panel/ctrlstate?json=1").verdict,
              DigestVerifier::Verdict::ok);
    const std::string second = session.authorization("POST", "/rw/mastership?action=request");
    EXPECT_NE(second.find("nc=00000002"), std::string::npos) << second;
    const auto r = verifier.verify(second, "POST", "/rw/mastership?action=request");
    EXPECT_EQ(r.verdict, DigestVerifier::Verdict::ok);
    EXPECT_EQ(r.nc, 2u);

    // A replayed nc, another URI, a wrong password: rejected.
    EXPECT_EQ(verifier.verify(second, "POST", "/rw/mastership?action=request").verdict,
              DigestVerifier::Verdict::rejected);
    EXPECT_EQ(verifier.verify(session.authorization("GET", "/a"), "GET", "/b").verdict,
              DigestVerifier::Verdict::rejected);
    DigestSession wrong("Default User", "wrong");
    wrong.accept(*parse_challenge(verifier.challenge(false).header));
    EXPECT_EQ(verifier.verify(wrong.authorization("GET", "/a"), "GET", "/a").verdict,
              DigestVerifier::Verdict::rejected);

    // Right credentials on an expired nonce: stale.
    verifier.expire_nonces();
    EXPECT_EQ(verifier.verify(session.authorization("GET", "/a"), "GET", "/a").verdict,
              DigestVerifier::Verdict::stale);
    EXPECT_EQ(verifier.verify("", "GET", "/a").verdict, DigestVerifier::Verdict::missing);
}

TEST(Digest, RefusesUnsupportedChallenges) {
    DigestSession s("u", "p");
    DigestChallenge c;
    c.realm = "r";
    c.nonce = "n";
    c.algorithm = "SHA-256";
    EXPECT_THROW(s.accept(c), std::invalid_argument);
    c.algorithm = "MD5";
    c.qop = {"auth-int"};
    EXPECT_THROW(s.accept(c), std::invalid_argument);
}

TEST(Url, FormRoundTrip) {
    const FormFields f{{"modulepath", "$HOME/a b.mod"}, {"value", "[1,2]&x=\"y+z\"%"}};
    const std::string encoded = form_encode(f);
    EXPECT_EQ(encoded.rfind("modulepath=$HOME/a%20b.mod&value=", 0), 0u) << encoded;
    EXPECT_EQ(parse_form(encoded), f);
    EXPECT_EQ(percent_decode("a+b%2", true), "a b%2");
}

// ---- Routes -------------------------------------------------------------------------------------

// Found by fuzzing (tests/fuzz/corpus/rws_http/utf8_*.http): a reply's JSON echoes request bytes
// (an unknown target, the Host header, a module path) and threw on bytes that are not UTF-8.
TEST(RwsRoutes, RequestBytesThatAreNotUtf8AreAnsweredNotThrown) {
    struct HeldHere : MastershipGate {
        bool held_by_caller() const override { return true; }
        bool held_elsewhere() const override { return false; }
        bool request() override { return true; }
        void release() override {}
    } gate;
    InMemoryController controller;
    const std::string replacement = "\xEF\xBF\xBD";  // U+FFFD

    const RouteReply unknown =
        route({"GET", "/rw/\xff", "", "127.0.0.1"}, controller, gate, "T_ROB1");
    EXPECT_EQ(unknown.status, 404u);
    EXPECT_NE(unknown.body.find("no resource /rw/" + replacement), std::string::npos)
        << unknown.body;

    const RouteReply state =
        route({"GET", "/rw/panel/ctrlstate", "", "12\xb7.0.0.1"}, controller, gate, "T_ROB1");
    EXPECT_EQ(state.status, 200u);
    EXPECT_NE(state.body.find("http://12" + replacement), std::string::npos) << state.body;

    const RouteReply load =
        route({"POST", "/rw/rapid/tasks/T_ROB1?action=loadmod", "modulepath=%FF.mod", "127.0.0.1"},
              controller, gate, "T_ROB1");
    EXPECT_EQ(load.status, 400u);
    EXPECT_NE(load.body.find("modulepath '" + replacement + ".mod'"), std::string::npos)
        << load.body;
}

// ---- Client against server ---------------------------------------------------------------------

TEST_F(RwsTest, DigestHandshakeThenSessionCookie) {
    EXPECT_EQ(client().controller_state(), ControllerState::motoron);
    EXPECT_EQ(client().execution_state().state, ExecutionState::stopped);
    EXPECT_EQ(client().controller_state(), ControllerState::motoron);

    const RwsServerStats s = server_->stats();
    EXPECT_EQ(s.challenges, 1u);     // one 401 for the whole conversation
    EXPECT_EQ(s.digest_logins, 1u);  // then the session cookie
    EXPECT_EQ(s.sessions_opened, 1u);
    EXPECT_EQ(s.requests, 4u);
    EXPECT_EQ(client().stats().connects, 1u);  // keep-alive
}

TEST_F(RwsTest, WrongPasswordIsAnAuthError) {
    RwsClientConfig c = client_config();
    c.password = "not-robotics";
    RwsClient bad(c);
    const RwsError e = rws_error([&] { bad.controller_state(); });
    EXPECT_EQ(e.kind(), RwsErrorKind::auth);
    EXPECT_EQ(e.http_status(), 401);
    EXPECT_NE(
        std::string(e.what()).find("authentication failed for user Default User at " + where()),
        std::string::npos)
        << e.what();
    EXPECT_EQ(server_->stats().rejected, 1u);
}

TEST_F(RwsTest, WithoutCookiesTheNonceIsReusedWithIncreasingNc) {
    RwsServerConfig config;
    config.session_cookies = false;
    start(config);
    for (int i = 0; i < 5; ++i) client().controller_state();
    const RwsServerStats s = server_->stats();
    EXPECT_EQ(s.challenges, 1u);
    EXPECT_EQ(s.digest_logins, 5u);
    EXPECT_EQ(s.max_nc, 5u);
    EXPECT_EQ(client().stats().requests, 6u);
}

TEST_F(RwsTest, StaleNonceIsRetriedTransparentlyAndKeepsTheSession) {
    RwsServerConfig config;
    config.session_cookies = false;
    start(config);
    client().request_mastership();
    server_->expire_nonces();
    client().upload_file("Good.mod", good_module);  // stale -> new nonce -> retried
    client().load_module("Good.mod");               // mastership survived the new nonce
    EXPECT_EQ(client().stats().stale_retries, 1u);
    EXPECT_EQ(server_->stats().stale_challenges, 1u);
    EXPECT_TRUE(has_module(client().modules(), "Good"));
}

TEST_F(RwsTest, ExpiredSessionLogsInAgain) {
    client().controller_state();
    server_->end_sessions();
    EXPECT_EQ(client().controller_state(), ControllerState::motoron);
    EXPECT_EQ(client().stats().challenges, 2u);
    EXPECT_EQ(server_->stats().sessions_opened, 2u);
}

TEST_F(RwsTest, UploadAndLoadAGoodModule) {
    load_good();
    EXPECT_TRUE(has_module(client().modules(), "Good"));
    EXPECT_TRUE(client().build_errors().empty());
    EXPECT_EQ(client().download_file("Good.mod"), good_module);
    const auto m = controller_->module("Good");
    ASSERT_TRUE(m);
    EXPECT_NE(m->find_routine("main"), nullptr);

    client().unload_module("Good");
    EXPECT_FALSE(has_module(client().modules(), "Good"));
    EXPECT_EQ(rws_error([&] { client().unload_module("Good"); }).kind(), RwsErrorKind::not_found);
}

TEST_F(RwsTest, ModuleWithASyntaxErrorIsABuildErrorNamingTheLine) {
    client().request_mastership();
    client().upload_file("Bad.mod", bad_module);
    const RwsError e = rws_error([&] { client().load_module("Bad.mod"); });
    EXPECT_EQ(e.kind(), RwsErrorKind::build);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("build error in Bad line 4"), std::string::npos) << msg;
    EXPECT_NE(msg.find(where()), std::string::npos) << msg;
    ASSERT_FALSE(e.build_errors().empty());
    EXPECT_EQ(e.build_errors().front().module, "Bad");
    EXPECT_EQ(e.build_errors().front().row, 4u);
    EXPECT_FALSE(has_module(client().modules(), "Bad"));
    EXPECT_EQ(client().build_errors().front().row, 4u);
}

TEST_F(RwsTest, ModuleUsingAnotherModulesDataBuildsAgainstTheTask) {
    load_good();
    client().upload_file("Chunk.mod",
                         "MODULE Chunk\n  PROC Chunk()\n    nLayer := 2;\n  ENDPROC\nENDMODULE\n");
    client().load_module("Chunk.mod");  // nLayer is Good's
    client().upload_file("Lost.mod",
                         "MODULE Lost\n  PROC Lost()\n    nMissing := 2;\n  ENDPROC\nENDMODULE\n");
    const RwsError e = rws_error([&] { client().load_module("Lost.mod"); });
    EXPECT_EQ(e.kind(), RwsErrorKind::build);
    EXPECT_NE(std::string(e.what()).find("Lost line 3"), std::string::npos) << e.what();
}

TEST_F(RwsTest, LoadingWithoutMastershipIsAMastershipError) {
    client().upload_file("Good.mod", good_module);
    const RwsError e = rws_error([&] { client().load_module("Good.mod"); });
    EXPECT_EQ(e.kind(), RwsErrorKind::mastership);
    EXPECT_EQ(e.http_status(), 403);
    EXPECT_NE(std::string(e.what()).find("not held by this client"), std::string::npos) << e.what();
}

TEST_F(RwsTest, MastershipHeldElsewhereIsAClearError) {
    server_->set_mastership_held_elsewhere(true);
    const RwsError e = rws_error([&] { client().request_mastership(); });
    EXPECT_EQ(e.kind(), RwsErrorKind::mastership);
    EXPECT_NE(std::string(e.what()).find("RAPID mastership is held by another client"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(where()), std::string::npos) << e.what();
    server_->set_mastership_held_elsewhere(false);

    // Another client's session holds it until it releases.
    RwsClient other(client_config());
    other.request_mastership();
    EXPECT_EQ(rws_error([&] { client().request_mastership(); }).kind(), RwsErrorKind::mastership);
    other.release_mastership();
    client().request_mastership();
    EXPECT_TRUE(client().holds_mastership());
    EXPECT_TRUE(server_->mastership_held());
    client().logout();  // ends the session: mastership goes with it
    EXPECT_FALSE(server_->mastership_held());
}

TEST_F(RwsTest, StartStopAndReadExecutionState) {
    load_good();
    client().reset_program_pointer();
    EXPECT_TRUE(controller_->program_pointer_at_main());
    StartOptions o;
    o.cycle = "once";
    client().start_execution(o);
    ExecutionInfo e = client().execution_state();
    EXPECT_EQ(e.state, ExecutionState::running);
    EXPECT_EQ(e.cycle, "once");
    EXPECT_EQ(controller_->start_count(), 1);
    client().stop_execution();
    EXPECT_EQ(client().execution_state().state, ExecutionState::stopped);

    // The simulator changes the controller state; start is then refused.
    controller_->set_controller_state(ControllerState::motoroff);
    EXPECT_EQ(client().controller_state(), ControllerState::motoroff);
    const RwsError refused = rws_error([&] { client().start_execution(); });
    EXPECT_EQ(refused.kind(), RwsErrorKind::state);
    EXPECT_NE(std::string(refused.what()).find("motors are not on"), std::string::npos)
        << refused.what();
    controller_->set_controller_state(ControllerState::guardstop);
    EXPECT_EQ(client().controller_state(), ControllerState::guardstop);
    controller_->set_execution_state(ExecutionState::running);
    EXPECT_EQ(client().execution_state().state, ExecutionState::running);
}

TEST_F(RwsTest, WriteAndReadPersData) {
    load_good();
    EXPECT_EQ(client().symbol("Good", "nLayer"), "0");
    client().set_symbol("Good", "nLayer", "42");
    EXPECT_EQ(client().symbol("Good", "nLayer"), "42");
    EXPECT_EQ(client().symbol("good", "NLAYER"), "42");  // RAPID names are case-insensitive
    EXPECT_EQ(client().symbol("Good", "sJob"), "\"none\"");
    client().set_symbol("Good", "sJob", "\"job 7 & co\"");
    EXPECT_EQ(client().symbol("Good", "sJob"), "\"job 7 & co\"");

    const RwsError type = rws_error([&] { client().set_symbol("Good", "nLayer", "\"text\""); });
    EXPECT_EQ(type.kind(), RwsErrorKind::state);
    EXPECT_NE(std::string(type.what()).find("is not a num value"), std::string::npos)
        << type.what();
    EXPECT_EQ(rws_error([&] { client().set_symbol("Good", "nPasses", "4"); }).kind(),
              RwsErrorKind::state);  // CONST
    EXPECT_EQ(rws_error([&] { client().symbol("Good", "nNothing"); }).kind(),
              RwsErrorKind::not_found);
    EXPECT_EQ(client().symbol("Good", "nLayer"), "42");

    client().release_mastership();
    EXPECT_EQ(rws_error([&] { client().set_symbol("Good", "nLayer", "1"); }).kind(),
              RwsErrorKind::mastership);
}

TEST_F(RwsTest, ReopensAKeepAliveConnectionTheServerClosed) {
    RwsServerConfig config;
    config.idle_timeout = 50ms;
    start(config);
    client().controller_state();
    ASSERT_TRUE(eventually([&] { return server_->stats().idle_closes == 1; }));  // dropped idle
    EXPECT_EQ(client().controller_state(), ControllerState::motoron);
    EXPECT_EQ(client().stats().connects, 2u);
}

TEST_F(RwsTest, ServerNotRunningIsATransportErrorNamingHostAndPort) {
    const std::string address = where();
    client();
    server_.reset();  // nothing listens on that port any more
    const RwsError e = rws_error([&] { client().controller_state(); });
    EXPECT_EQ(e.kind(), RwsErrorKind::transport);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("read the controller state at " + address), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot connect"), std::string::npos) << msg;
}

TEST(RwsTimeout, SilentPeerIsATransportTimeout) {
    // A listener that never accepts: the kernel completes the connection, nobody answers.
    const int silent = ::socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(silent, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    socklen_t len = sizeof addr;
    ASSERT_EQ(::bind(silent, reinterpret_cast<sockaddr*>(&addr), len), 0);
    ASSERT_EQ(::listen(silent, 4), 0);
    ASSERT_EQ(::getsockname(silent, reinterpret_cast<sockaddr*>(&addr), &len), 0);
    RwsClientConfig c;
    c.port = ntohs(addr.sin_port);
    c.request_timeout = 200ms;
    RwsClient client(c);
    const auto t0 = std::chrono::steady_clock::now();
    const RwsError e = rws_error([&] { client.execution_state(); });
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
    EXPECT_EQ(e.kind(), RwsErrorKind::transport);
    EXPECT_NE(std::string(e.what()).find("no response within 200 ms"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(c.port)), std::string::npos)
        << e.what();
    ::close(silent);
}
