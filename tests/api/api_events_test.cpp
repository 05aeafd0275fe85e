// subscribe/unsubscribe and published events over the real Unix socket: state changes in order,
// progress coalesced to the configured rate with the latest value delivered, topic filters,
// several subscribers, and a slow subscriber cut off without holding anyone else up.
#include "api_server_fixture.hpp"

#include <filesystem>
#include <thread>

using namespace fibrecell::api;
using nlohmann::json;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using fibrecell::test::call_error_code;

namespace {

struct Received {
    ApiNotification n;
    Clock::time_point at;
};

// Notifications until none arrives for `quiet`.
std::vector<Received> collect(ApiClient& c, std::chrono::milliseconds quiet = 300ms) {
    std::vector<Received> out;
    while (auto n = c.next_notification(quiet)) out.push_back({std::move(*n), Clock::now()});
    return out;
}

class ApiEventsTest : public fibrecell::test::ApiServerTest {
  protected:
    ApiEventsTest() : ApiServerTest("api-ev") {}
    ApiClient subscriber(const json& topics) {
        auto c = client();
        c.call("subscribe", {{"topics", topics}});
        return c;
    }
    void state(const std::string& job, int seq, const std::string& s = "printing") {
        server_->publish({job, notify::job_state, {{"job", job}, {"seq", seq}, {"state", s}}});
    }
    void progress(const std::string& job, int value) {
        server_->publish(
            {job, notify::job_progress, {{"job", job}, {"value", value}}, Delivery::latest});
    }
};

}  // namespace

TEST_F(ApiEventsTest, SubscribeAndUnsubscribeReportTheTopics) {
    start();
    auto c = client();
    EXPECT_EQ(c.call("subscribe"), (json{{"topics", {"*"}}}));
    EXPECT_EQ(c.call("subscribe", {{"topics", {"j-1", "cell"}}}),
              (json{{"topics", {"*", "cell", "j-1"}}}));
    EXPECT_EQ(c.call("unsubscribe", {{"topics", {"*"}}}), (json{{"topics", {"cell", "j-1"}}}));
    EXPECT_EQ(c.call("unsubscribe"), (json{{"topics", json::array()}}));
    EXPECT_EQ(call_error_code(c, "subscribe", {{"topics", json::array()}}), errc::invalid_params);
    EXPECT_EQ(call_error_code(c, "subscribe", {{"topics", {1}}}), errc::invalid_params);
    EXPECT_EQ(call_error_code(c, "subscribe", {{"topics", "j-1"}}), errc::invalid_params);
    EXPECT_EQ(call_error_code(c, "subscribe", {{"job", "j-1"}}), errc::invalid_params);
}

TEST_F(ApiEventsTest, NotificationsAreJsonRpcWithoutId) {
    start();
    auto c = subscriber({"j-1"});
    state("j-1", 0, "planning");
    const auto m = c.read_message(5s);
    ASSERT_TRUE(m);
    EXPECT_EQ(*m, (json{{"jsonrpc", "2.0"},
                        {"method", "notify.job_state"},
                        {"params", {{"job", "j-1"}, {"seq", 0}, {"state", "planning"}}}}));
}

TEST_F(ApiEventsTest, StateChangesAllArriveInOrder) {
    start();
    auto c = subscriber({"j-1"});
    constexpr int kCount = 300;
    for (int i = 0; i < kCount; ++i) state("j-1", i);
    const auto got = collect(c);
    ASSERT_EQ(got.size(), static_cast<std::size_t>(kCount));
    for (int i = 0; i < kCount; ++i) {
        EXPECT_EQ(got[i].n.method, notify::job_state);
        EXPECT_EQ(got[i].n.params["seq"], i);
    }
    EXPECT_EQ(server_->stats().notifications_coalesced, 0u);
}

TEST_F(ApiEventsTest, ProgressIsCoalescedToTheRateAndTheLatestArrives) {
    config_.progress_rate_hz = 20;  // 50 ms per event: the test's time scale
    start();
    auto c = subscriber({"*"});
    constexpr int kCount = 150;
    const auto begin = Clock::now();
    for (int i = 0; i < kCount; ++i) {
        progress("j-1", i);
        std::this_thread::sleep_for(2ms);
    }
    const auto elapsed = Clock::now() - begin;
    const auto got = collect(c);
    ASSERT_GE(got.size(), 2u);
    EXPECT_EQ(got.front().n.params["value"], 0);          // the first goes out at once
    EXPECT_EQ(got.back().n.params["value"], kCount - 1);  // the last is never lost
    for (std::size_t i = 1; i < got.size(); ++i)
        EXPECT_GT(got[i].n.params["value"], got[i - 1].n.params["value"]);
    const auto allowed = static_cast<std::size_t>(elapsed / 50ms) + 2;
    EXPECT_LE(got.size(), allowed)
        << "publishing took " << std::chrono::duration<double>(elapsed).count() << " s";
    EXPECT_GT(server_->stats().notifications_coalesced, 0u);
}

TEST_F(ApiEventsTest, ProgressAtTheDefaultRateIsTwoPerSecond) {
    start();  // progress_rate_hz = 2
    auto c = subscriber({"j-1"});
    for (int i = 0; i < 40; ++i) progress("j-1", i);
    const auto got = collect(c, 800ms);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].n.params["value"], 0);
    EXPECT_EQ(got[1].n.params["value"], 39);
    EXPECT_GE(got[1].at - got[0].at, 450ms);  // held for the rest of the 500 ms interval
}

TEST_F(ApiEventsTest, AHeldProgressGoesOutBeforeTheNextStateChange) {
    start();  // 2 per second: the held value would otherwise wait ~500 ms
    auto c = subscriber({"j-1"});
    progress("j-1", 10);
    progress("j-1", 11);  // held
    progress("j-2", 5);   // another topic: not subscribed, never sent
    state("j-1", 0, "completed");
    const auto got = collect(c, 700ms);
    ASSERT_EQ(got.size(), 3u);
    EXPECT_EQ(got[0].n.params["value"], 10);
    EXPECT_EQ(got[1].n.params["value"], 11);
    EXPECT_EQ(got[2].n.method, notify::job_state);
    EXPECT_EQ(got[2].n.params["state"], "completed");
}

TEST_F(ApiEventsTest, TwoSubscribersBothGetEveryEventAndOthersNone) {
    start();
    auto a = subscriber({"j-1"});
    auto b = subscriber({"*"});
    auto bystander = client();
    for (int i = 0; i < 20; ++i) state("j-1", i);
    const auto got_a = collect(a);
    const auto got_b = collect(b);
    ASSERT_EQ(got_a.size(), 20u);
    ASSERT_EQ(got_b.size(), 20u);
    for (int i = 0; i < 20; ++i) {
        EXPECT_EQ(got_a[i].n.params["seq"], i);
        EXPECT_EQ(got_b[i].n.params["seq"], i);
    }
    // The answer comes after anything published before the call: nothing came for the bystander.
    EXPECT_EQ(bystander.call("echo", {{"x", 1}}), (json{{"x", 1}}));
    EXPECT_FALSE(bystander.next_notification(50ms));
}

TEST_F(ApiEventsTest, TopicsSelectWhatAClientGets) {
    start();
    auto one = subscriber({"j-1"});
    auto cell = subscriber({"cell"});
    state("j-2", 0);
    state("j-1", 1);
    server_->publish({topic::cell, notify::cell_status, {{"robot", "idle"}}});
    const auto got_one = collect(one);
    ASSERT_EQ(got_one.size(), 1u);
    EXPECT_EQ(got_one[0].n.params["job"], "j-1");
    const auto got_cell = collect(cell);
    ASSERT_EQ(got_cell.size(), 1u);
    EXPECT_EQ(got_cell[0].n.method, notify::cell_status);
}

TEST_F(ApiEventsTest, UnsubscribeStopsTheEventsAndDropsHeldOnes) {
    config_.progress_rate_hz = 1;  // the held value would go out ~1 s after the first
    start();
    auto c = subscriber({"j-1"});
    state("j-1", 0);
    progress("j-1", 1);  // sent
    progress("j-1", 2);  // held ...
    ASSERT_EQ(collect(c, 100ms).size(), 2u);
    EXPECT_EQ(c.call("unsubscribe", {{"topics", {"j-1"}}}), (json{{"topics", json::array()}}));
    state("j-1", 3);
    EXPECT_EQ(c.call("echo", {{"x", 1}}), (json{{"x", 1}}));
    EXPECT_FALSE(c.next_notification(1200ms));  // ... and never delivered after unsubscribing
}

TEST_F(ApiEventsTest, ASlowSubscriberIsDisconnectedWhileOthersAreAnswered) {
    config_.max_client_queue_bytes = 64 << 10;
    start();
    auto slow = subscriber({"*"});  // never reads again
    auto normal = client();
    const std::string filler(4000, 'f');
    for (int i = 0; i < 600; ++i)  // 2.4 MB: far more than the socket buffers and the queue
        server_->publish({"j-1", notify::log, {{"seq", i}, {"text", filler}}});
    const auto deadline = Clock::now() + 5s;
    while (server_->stats().dropped_slow == 0 && Clock::now() < deadline)
        EXPECT_EQ(normal.call("echo", {{"alive", true}}), (json{{"alive", true}}));
    EXPECT_EQ(server_->stats().dropped_slow, 1u);
    EXPECT_EQ(normal.call("echo", {{"after", true}}), (json{{"after", true}}));
    EXPECT_EQ(server_->stats().clients, 1u);
    EXPECT_TRUE(slow.wait_closed(5s));  // what was already sent, then EOF
}
