// JSON-RPC 2.0 over the real Unix socket: every error code, batches, notifications, oversized
// requests, async handlers. The server runs on an io_context thread; clients are ApiClient.
#include "api_server_fixture.hpp"
#include "daemon/api/json_rpc.hpp"
#include "daemon/api/params.hpp"

#include <atomic>
#include <filesystem>
#include <future>
#include <thread>

using namespace fibrecell::api;
using nlohmann::json;
using namespace std::chrono_literals;
using fibrecell::test::call_error_code;

namespace {

class ApiProtocolTest : public fibrecell::test::ApiServerTest {
  protected:
    ApiProtocolTest() : ApiServerTest("api-proto") {}
    void TearDown() override {
        ApiServerTest::TearDown();
        for (auto& t : workers_) t.join();
    }
    void add_methods(ApiServer& server) override {
        server.add_method("count",
                          [this](const json&, const CallContext&) { return json(++count_); });
        server.add_method(
            "count.get", [this](const json&, const CallContext&) { return json(count_.load()); });
        server.add_method("typed", [](const json& params, const CallContext& ctx) {
            ParamReader p(ctx.method, params);
            const auto n = p.integer_or("n", 0, 0, 10);
            const auto name = p.string("name");
            p.finish();
            return json{{"n", n}, {"name", name}};
        });
        server.add_method("fail.internal", [](const json&, const CallContext&) -> json {
            throw std::runtime_error("disk on fire");
        });
        server.add_method("fail.conflict", [](const json&, const CallContext&) -> json {
            throw ApiError(errc::conflict, "job j-7 is printing; pause it first",
                           json{{"state", "printing"}});
        });
        server.add_method("fail.not_found", [](const json&, const CallContext&) -> json {
            throw ApiError::not_found("no job j-99");
        });
        server.add_method("fail.unavailable", [](const json&, const CallContext&) -> json {
            throw ApiError::unavailable("the service is draining");
        });
        server.add_async_method(
            "later", [this](const json& params, const CallContext&, Responder r) {
                const auto delay = std::chrono::milliseconds(params.value("ms", 20));
                workers_.emplace_back([r, delay, params] {
                    std::this_thread::sleep_for(delay);
                    if (params.value("fail", false))
                        r.error(ApiError::conflict("too late"));
                    else
                        r.result({{"thread", "worker"}});
                });
            });
        server.add_async_method("dropped", [](const json&, const CallContext&, Responder) {});
    }

    // The error object of the next message, which must be an error response.
    static json next_error(ApiClient& c) {
        const auto m = c.read_message(5s);
        if (!m || !m->contains("error")) return json{{"missing", m ? *m : json()}};
        return *m;
    }

    std::vector<std::thread> workers_;  // joined after the server is gone
    std::atomic<int> count_{0};
};

}  // namespace

TEST_F(ApiProtocolTest, ResultEchoesTheIdOfAnyAllowedType) {
    start();
    auto c = client();
    EXPECT_EQ(c.call("echo", {{"a", 1}}), (json{{"a", 1}}));
    c.send_line(R"({"jsonrpc":"2.0","id":"abc","method":"echo","params":[1,2]})");
    EXPECT_EQ(*c.read_message(5s), (json{{"jsonrpc", "2.0"}, {"id", "abc"}, {"result", {1, 2}}}));
    c.send_line(R"({"jsonrpc":"2.0","id":null,"method":"echo"})");
    EXPECT_EQ(*c.read_message(5s),
              (json{{"jsonrpc", "2.0"}, {"id", nullptr}, {"result", json::object()}}));
}

TEST_F(ApiProtocolTest, MalformedJsonIsAParseErrorAndTheConnectionStaysUsable) {
    start();
    auto c = client();
    c.send_line(R"({"jsonrpc":"2.0","id":1,"method":"echo",)");
    const json e = next_error(c);
    EXPECT_EQ(e["id"], nullptr);
    EXPECT_EQ(e["error"]["code"], errc::parse_error);
    EXPECT_NE(e["error"]["message"].get<std::string>().find("parse error"), std::string::npos) << e;
    EXPECT_EQ(c.call("echo", {{"still", "here"}}), (json{{"still", "here"}}));
}

// Found by fuzzing (tests/fuzz/corpus/json_rpc/number_overflow.jsonl): nlohmann reports a number
// no double holds with out_of_range, not parse_error; it escaped the connection's handler and
// ended fibrecelld.
TEST_F(ApiProtocolTest, ANumberBeyondDoubleIsAParseErrorAndTheConnectionStaysUsable) {
    start();
    auto c = client();
    c.send_line(R"({"jsonrpc":"2.0","id":1,"method":"echo","params":[1e400]})");
    const json e = next_error(c);
    EXPECT_EQ(e["id"], nullptr);
    EXPECT_EQ(e["error"]["code"], errc::parse_error);
    EXPECT_EQ(e["error"]["message"], "number overflow parsing '1e400'") << e;
    EXPECT_EQ(c.call("echo", {{"still", "here"}}), (json{{"still", "here"}}));
}

TEST_F(ApiProtocolTest, InvalidRequestsAreAnsweredWithTheirIdWhenReadable) {
    start();
    auto c = client();
    struct Case {
        const char* line;
        json id;
        const char* why;
    };
    const Case cases[] = {
        {R"(42)", nullptr, "a request must be a JSON object"},
        {R"({"id":1,"method":"echo"})", 1, "\"jsonrpc\" must be \"2.0\""},
        {R"({"jsonrpc":"1.0","id":2,"method":"echo"})", 2, "\"jsonrpc\" must be \"2.0\""},
        {R"({"jsonrpc":"2.0","id":3,"method":7})", 3, "\"method\" must be a string"},
        {R"({"jsonrpc":"2.0","id":4})", 4, "\"method\" must be a string"},
        {R"({"jsonrpc":"2.0","id":5,"method":"echo","params":"x"})", 5,
         "\"params\" must be an object or an array"},
        {R"({"jsonrpc":"2.0","id":{"a":1},"method":"echo"})", nullptr,
         "id must be a string, a number or null"},
        {R"({"jsonrpc":"2.0","id":6,"method":"echo","param":{}})", 6, "unknown member \"param\""},
        // Without an id the request is still invalid, and said so (there is no method to run).
        {R"({"jsonrpc":"2.0"})", nullptr, "\"method\" must be a string"},
    };
    for (const auto& k : cases) {
        c.send_line(k.line);
        const json e = next_error(c);
        EXPECT_EQ(e["id"], k.id) << k.line;
        EXPECT_EQ(e["error"]["code"], errc::invalid_request) << k.line;
        EXPECT_EQ(e["error"]["message"], std::string("invalid request: ") + k.why) << k.line;
    }
}

TEST_F(ApiProtocolTest, DeeplyNestedJsonIsRefusedBeforeParsing) {
    start();
    auto c = client();
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    c.send_line(R"({"jsonrpc":"2.0","id":1,"method":"echo","params":{"a":)" + deep + "}}");
    const json e = next_error(c);
    EXPECT_EQ(e["error"]["code"], errc::invalid_request);
    EXPECT_EQ(e["error"]["message"], "invalid request: JSON nested deeper than 128 levels");
    // Brackets inside strings do not count; 100 levels are fine.
    const std::string text = std::string(300, '[');
    const json nested = json::parse(std::string(100, '[') + std::string(100, ']'));
    EXPECT_EQ(c.call("echo", {{"s", text}, {"n", nested}}), (json{{"s", text}, {"n", nested}}));
    EXPECT_EQ(nesting_depth(R"({"a":"[{\"[","b":[[1]]})"), 3u);
}

TEST_F(ApiProtocolTest, UnknownMethodIsMethodNotFound) {
    start();
    auto c = client();
    try {
        c.call("job.explode");
        FAIL() << "no error";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::method_not_found);
        EXPECT_STREQ(e.what(), "method not found: job.explode");
    }
}

TEST_F(ApiProtocolTest, BadParamsAreInvalidParamsNamingTheMember) {
    start();
    auto c = client();
    EXPECT_EQ(c.call("typed", {{"name", "x"}, {"n", 3}}), (json{{"n", 3}, {"name", "x"}}));
    const std::pair<json, std::string> cases[] = {
        {json::object(), "typed: params.name is required (a string)"},
        {{{"name", 5}}, "typed: params.name must be a string"},
        {{{"name", "x"}, {"n", 11}}, "typed: params.n must be in [0, 10], got 11"},
        {{{"name", "x"}, {"n", 1.5}}, "typed: params.n must be a whole number"},
        {{{"name", "x"}, {"colour", "red"}}, "typed: params.colour is not a parameter of typed"},
        {json::array({1}), "typed: params must be an object with named members"},
    };
    for (const auto& [params, message] : cases) {
        try {
            c.call("typed", params);
            ADD_FAILURE() << "no error for " << params;
        } catch (const ApiCallError& e) {
            EXPECT_EQ(e.code(), errc::invalid_params);
            EXPECT_EQ(std::string(e.what()), message);
        }
    }
}

TEST_F(ApiProtocolTest, AHandlerFailureIsAnInternalErrorAndNothingElseBreaks) {
    start();
    auto c = client();
    try {
        c.call("fail.internal");
        FAIL() << "no error";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::internal_error);
        EXPECT_STREQ(e.what(), "internal error in fail.internal: disk on fire");
    }
    EXPECT_EQ(c.call("count"), 1);
    EXPECT_EQ(server_->stats().errors, 1u);
}

TEST_F(ApiProtocolTest, ApplicationErrorsCarryCodeMessageAndData) {
    start();
    auto c = client();
    try {
        c.call("fail.conflict");
        FAIL() << "no error";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), -32003);
        EXPECT_STREQ(e.what(), "job j-7 is printing; pause it first");
        EXPECT_EQ(e.data(), (json{{"state", "printing"}}));
    }
    EXPECT_EQ(call_error_code(c, "fail.not_found"), -32002);
    EXPECT_EQ(call_error_code(c, "fail.unavailable"), -32005);
    EXPECT_EQ(error_name(-32002), "not_found");
    EXPECT_EQ(error_name(-32004), "too_large");
}

TEST_F(ApiProtocolTest, OversizedRequestIsAnsweredThenTheConnectionCloses) {
    config_.max_request_bytes = 1024;
    start();
    auto c = client();
    const std::string big(5000, 'x');
    try {
        c.call("echo", {{"blob", big}});
        FAIL() << "no error";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::too_large);
        EXPECT_NE(std::string(e.what()).find("at most 1024 bytes (api.max_request_bytes)"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(c.wait_closed(5s));
    EXPECT_EQ(server_->stats().oversized, 1u);

    // An unterminated line is cut off as soon as it passes the limit.
    auto d = client();
    d.send_line(std::string(1500, ' ').append("x"));  // no JSON, no chance to finish
    EXPECT_EQ(next_error(d)["error"]["code"], errc::too_large);

    // Other clients are unaffected.
    auto e = client();
    EXPECT_EQ(e.call("count"), 1);
}

TEST_F(ApiProtocolTest, ARequestOfExactlyTheLimitIsAccepted) {
    config_.max_request_bytes = 1024;
    start();
    auto c = client();
    const std::string head = R"({"jsonrpc":"2.0","id":1,"method":"echo","params":{"p":")";
    const std::string tail = R"("}})";
    const std::string line = head + std::string(1024 - head.size() - tail.size(), 'y') + tail;
    ASSERT_EQ(line.size(), 1024u);
    c.send_line(line);
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m);
    EXPECT_EQ((*m)["result"]["p"].get<std::string>().size(), 1024 - head.size() - tail.size());
}

TEST_F(ApiProtocolTest, BatchAnswersEveryRequestInOneArray) {
    start();
    auto c = client();
    const json batch = json::array({
        {{"jsonrpc", "2.0"}, {"id", 1}, {"method", "echo"}, {"params", {{"a", 1}}}},
        {{"jsonrpc", "2.0"}, {"method", "count"}},  // a notification: no entry
        {{"jsonrpc", "2.0"}, {"id", 2}, {"method", "nope"}},
        17,
        {{"jsonrpc", "2.0"}, {"id", 3}, {"method", "later"}, {"params", {{"ms", 10}}}},
    });
    c.send_line(batch.dump());
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m);
    ASSERT_TRUE(m->is_array()) << *m;
    ASSERT_EQ(m->size(), 4u);
    EXPECT_EQ((*m)[0], (json{{"jsonrpc", "2.0"}, {"id", 1}, {"result", {{"a", 1}}}}));
    EXPECT_EQ((*m)[1]["error"]["code"], errc::method_not_found);
    EXPECT_EQ((*m)[2]["error"]["code"], errc::invalid_request);
    EXPECT_EQ((*m)[2]["id"], nullptr);
    EXPECT_EQ((*m)[3]["result"]["thread"], "worker");  // async entries complete the batch
    EXPECT_EQ(count_.load(), 1);
}

TEST_F(ApiProtocolTest, EmptyBatchIsOneInvalidRequest) {
    start();
    auto c = client();
    c.send_line("[]");
    const json e = next_error(c);
    EXPECT_FALSE(e.is_array());
    EXPECT_EQ(e["error"]["code"], errc::invalid_request);
    EXPECT_EQ(e["error"]["message"], "invalid request: an empty batch");
}

TEST_F(ApiProtocolTest, ABatchOverTheLimitIsRefusedWholeBeforeAnyCallRuns) {
    config_.max_batch_calls = 5;
    start();
    auto c = client();
    json batch = json::array();
    for (int i = 0; i < 6; ++i) batch.push_back({{"jsonrpc", "2.0"}, {"id", i}, {"method", "count"}});
    c.send_line(batch.dump());
    const json e = next_error(c);
    EXPECT_FALSE(e.is_array());
    EXPECT_EQ(e["error"]["code"], errc::invalid_request);
    EXPECT_EQ(e["error"]["message"],
              "invalid request: a batch of 6 calls; at most 5 (api.max_batch_calls)");
    EXPECT_EQ(c.call("count.get"), 0);  // none of it ran
    batch.erase(batch.begin());  // five: at the limit
    c.send_line(batch.dump());
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m && m->is_array()) << (m ? m->dump() : "nothing");
    EXPECT_EQ(m->size(), 5u);
    EXPECT_EQ(c.call("count.get"), 5);
}

TEST_F(ApiProtocolTest, ABatchWhoseAnswersDoNotFitIsOneTooLargeErrorAfterItsCallsRan) {
    config_.max_client_queue_bytes = 64 << 10;
    start();
    auto c = client();
    // Ten echoes of 10 KiB each: 100 KiB of answers against a 64 KiB queue.
    json batch = json::array();
    for (int i = 0; i < 10; ++i)
        batch.push_back({{"jsonrpc", "2.0"}, {"id", i}, {"method", "echo"},
                         {"params", {{"text", std::string(10 << 10, 'x')}}}});
    batch.push_back({{"jsonrpc", "2.0"}, {"id", 10}, {"method", "count"}});
    c.send_line(batch.dump());
    const json e = next_error(c);
    EXPECT_FALSE(e.is_array());
    EXPECT_EQ(e["error"]["code"], errc::too_large);
    EXPECT_NE(e["error"]["message"].get<std::string>().find("the calls were made"), std::string::npos)
        << e;
    EXPECT_EQ(c.call("count.get"), 1);  // the connection goes on, and the calls did run
}

TEST_F(ApiProtocolTest, NotificationsAreNeverAnswered) {
    start();
    auto c = client();
    c.notify("count");
    c.notify("count");
    c.notify("nope");                            // unknown: still silent
    c.notify("typed", {{"n", "not a number"}});  // invalid params: silent
    c.notify("fail.internal");                   // failing handler: silent
    c.send_line(R"([{"jsonrpc":"2.0","method":"count"},{"jsonrpc":"2.0","method":"count"}])");
    // The next message on the wire is the answer to this call: nothing came before it.
    c.send_line(R"({"jsonrpc":"2.0","id":99,"method":"count.get"})");
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m);
    EXPECT_EQ(*m, (json{{"jsonrpc", "2.0"}, {"id", 99}, {"result", 4}}));
    EXPECT_FALSE(c.read_message(50ms));
}

TEST_F(ApiProtocolTest, AsyncHandlerCompletesFromAnotherThreadWithoutBlockingOthers) {
    start();
    auto c = client();
    c.send_line(R"({"jsonrpc":"2.0","id":1,"method":"later","params":{"ms":100}})");
    c.send_line(R"({"jsonrpc":"2.0","id":2,"method":"echo","params":{"quick":true}})");
    const auto first = c.read_message(5s);
    const auto second = c.read_message(5s);
    ASSERT_TRUE(first && second);
    EXPECT_EQ((*first)["id"], 2);  // the sync call was not held up by the pending async one
    EXPECT_EQ((*second)["id"], 1);
    EXPECT_EQ((*second)["result"]["thread"], "worker");
    EXPECT_EQ(call_error_code(c, "later", {{"ms", 5}, {"fail", true}}), errc::conflict);
}

TEST_F(ApiProtocolTest, AsyncHandlerThatDropsItsResponderAnswersInternalError) {
    start();
    auto c = client();
    try {
        c.call("dropped");
        FAIL() << "no error";
    } catch (const ApiCallError& e) {
        EXPECT_EQ(e.code(), errc::internal_error);
        EXPECT_STREQ(e.what(), "internal error: dropped was dropped without an answer");
    }
}

TEST_F(ApiProtocolTest, PipelinedBlankAndCrlfLinesAreFine) {
    start();
    auto c = client();
    c.send_line(
        "\r\n   \n{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"count\"}\r\n"
        "{\"jsonrpc\":\"2.0\",\"id\":2,\"method\":\"count\"}");
    const auto a = c.read_message(5s);
    const auto b = c.read_message(5s);
    ASSERT_TRUE(a && b);
    EXPECT_EQ((*a)["result"], 1);
    EXPECT_EQ((*b)["result"], 2);
}

TEST_F(ApiProtocolTest, ServerAuthOnTheUnixSocketNeedsNoToken) {
    start();
    auto c = client();
    EXPECT_EQ(c.call("server.auth"), (json{{"authenticated", true}}));
}

TEST(ApiRegistry, ReservedAndDuplicateNamesAreRefused) {
    MethodRegistry r;
    const SyncHandler h = [](const json&, const CallContext&) { return json(); };
    EXPECT_THROW(r.add("server.auth", h), std::logic_error);
    EXPECT_THROW(r.add("subscribe", h), std::logic_error);
    EXPECT_THROW(r.add("rpc.discover", h), std::logic_error);
    r.add("job.list", h);
    EXPECT_THROW(r.add("job.list", h), std::logic_error);
    EXPECT_NE(r.find("job.list"), nullptr);
    EXPECT_EQ(r.find("job.get"), nullptr);
}
