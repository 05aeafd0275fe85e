// The print queue and the clear-cell rule (docs/queue.md), against fibrecelld over its socket on
// the simulated cell: queued jobs print in order, one per clear; nothing starts on a bed that holds
// a part, queued or by hand; the queue, its order and the bed survive a kill -9, and an unreadable
// queue file holds every start; an aborted print pauses the queue; bad calls are refused with what
// and why, and change nothing.
#include "service_fixture.hpp"

#include "daemon/api/api_error.hpp"

#include <gmock/gmock.h>

namespace fibrecell::test {
namespace service_queue_test {

using ::testing::HasSubstr;

// The refusal of a call: its code and message (code 0: it was not refused).
struct Refusal {
    int code = 0;
    std::string message;
};
Refusal refusal(const std::function<void()>& call) {
    try {
        call();
    } catch (const api::ApiCallError& e) {
        return {e.code(), e.what()};
    }
    return {};
}

std::vector<std::int64_t> queued(api::ApiClient& c) {
    const json q = c.call("queue.list");
    std::vector<std::int64_t> ids;
    for (const json& j : q.at("jobs")) ids.push_back(j.at("id").get<std::int64_t>());
    return ids;
}

TEST_F(ServiceTest, QueuedJobsPrintInOrderOnePerClearAndTheQueueSurvivesAKill) {
    const fs::path config = write_config("queue: {auto_start: after_clear}\n");
    start_service(config);
    std::int64_t a = 0, b = 0, c = 0;
    {
        api::ApiClient api = client();
        a = submit_bar(api, false);
        b = submit_bar(api, false);
        c = submit_bar(api, false);
        // A clear cell: the first starts as soon as it is planned.
        for (std::int64_t id : {a, b, c}) api.call("queue.add", {{"job", id}});
        ASSERT_TRUE(printed(wait_for_state(api, a, "completed", 120s)));
        ASSERT_EQ(wait_for_state(api, b, "planned").value("state", ""), "planned");

        // Its part is on the bed: the next one waits, whatever asks it to start.
        const json q = api.call("queue.resume");  // the queue looks for its next job again
        EXPECT_EQ(queued(api), (std::vector<std::int64_t>{b, c}));
        EXPECT_FALSE(q.at("bed").at("clear").get<bool>()) << q.dump();
        EXPECT_EQ(q.at("bed").at("job"), a);
        EXPECT_EQ(api.call("job.get", {{"job", b}}).value("state", ""), "planned");
        const Refusal by_hand = refusal([&] { api.call("job.start", {{"job", b}}); });
        EXPECT_EQ(by_hand.code, api::errc::conflict);
        EXPECT_THAT(by_hand.message, HasSubstr("not clear"));
        EXPECT_THAT(by_hand.message, HasSubstr("job " + std::to_string(a)));
        EXPECT_EQ(api.call("cell.status").at("bed").value("clear", true), false);
    }

    // kill -9 and a new start: the queue, its order and the bed as they were.
    service_->kill_now();
    start_service(config);
    api::ApiClient api = client();
    EXPECT_EQ(queued(api), (std::vector<std::int64_t>{b, c}));
    EXPECT_EQ(api.call("queue.list").at("bed").at("job"), a);
    EXPECT_EQ(api.call("job.get", {{"job", b}}).value("state", ""), "planned");

    api.call("queue.move", {{"job", c}, {"position", 1}});
    EXPECT_EQ(queued(api), (std::vector<std::int64_t>{c, b}));
    const Refusal not_queued = refusal([&] { api.call("queue.remove", {{"job", a}}); });
    EXPECT_EQ(not_queued.code, api::errc::conflict);
    EXPECT_THAT(not_queued.message, HasSubstr("is completed, not queued"));

    // The operator clears the bed: the next in the queue (now c) starts; it leaves the queue once
    // it prints. Paused there, so that the calls below meet it on the cell whatever the load.
    api.call("cell.clear");
    ASSERT_EQ(wait_for_state(api, c, "printing").value("state", ""), "printing");
    EXPECT_TRUE(eventually([&] { return queued(api) == std::vector<std::int64_t>{b}; }, 30s))
        << api.call("queue.list").dump();
    api.call("job.pause", {{"job", c}});
    ASSERT_EQ(wait_for_state(api, c, "paused").value("state", ""), "paused");
    for (const char* method : {"queue.move", "queue.remove"}) {
        json params = {{"job", c}};
        if (std::string(method) == "queue.move") params["position"] = 1;
        const Refusal r = refusal([&] { api.call(method, params); });
        EXPECT_EQ(r.code, api::errc::conflict) << method;
        EXPECT_THAT(r.message, HasSubstr("is paused, not queued")) << method;
    }
    const Refusal busy = refusal([&] { api.call("cell.clear"); });
    EXPECT_EQ(busy.code, api::errc::conflict);
    EXPECT_THAT(busy.message, HasSubstr("paused on the cell"));
    api.call("job.resume", {{"job", c}});
    ASSERT_TRUE(printed(wait_for_state(api, c, "completed", 120s)));

    api.call("cell.clear");
    ASSERT_TRUE(printed(wait_for_state(api, b, "completed", 120s)));
    const json q = api.call("queue.list");
    EXPECT_TRUE(q.at("jobs").empty()) << q.dump();
    EXPECT_EQ(q.at("bed").at("job"), b);
}

TEST_F(ServiceTest, AByHandQueueRefusesBadCallsAndPausesAfterAnAbortedPrint) {
    start_service(write_config());  // auto_start: manual, the default
    api::ApiClient api = client();
    const std::int64_t a = submit_bar(api, false);
    const std::int64_t b = submit_bar(api, false);
    const std::int64_t broken = submit_broken(api);
    api.call("queue.add", {{"job", a}});
    EXPECT_EQ(wait_for_state(api, broken, "failed").value("state", ""), "failed");

    // Bad calls: each refused with what and why, the queue as it was.
    const json before = api.call("queue.list");
    const Refusal unknown = refusal([&] { api.call("queue.add", {{"job", 99}}); });
    EXPECT_EQ(unknown.code, api::errc::not_found);
    EXPECT_THAT(unknown.message, HasSubstr("99"));
    const Refusal far = refusal([&] { api.call("queue.add", {{"job", b}, {"position", 7}}); });
    EXPECT_EQ(far.code, api::errc::invalid_params);
    EXPECT_THAT(far.message, HasSubstr("position"));
    const Refusal failed = refusal([&] { api.call("queue.add", {{"job", broken}}); });
    EXPECT_EQ(failed.code, api::errc::conflict);
    EXPECT_THAT(failed.message, HasSubstr("is failed"));
    const Refusal twice = refusal([&] { api.call("queue.add", {{"job", a}}); });
    EXPECT_EQ(twice.code, api::errc::conflict);
    EXPECT_THAT(twice.message, HasSubstr("queued already, at position 1"));
    const Refusal nowhere = refusal([&] { api.call("queue.move", {{"job", a}, {"position", 2}}); });
    EXPECT_EQ(nowhere.code, api::errc::invalid_params);
    const Refusal no_job = refusal([&] { api.call("queue.remove", {{"position", 1}}); });
    EXPECT_EQ(no_job.code, api::errc::invalid_params);
    EXPECT_THAT(no_job.message, HasSubstr("job"));
    EXPECT_EQ(api.call("queue.list"), before);

    // By hand: nothing starts until the operator says next.
    api.call("queue.add", {{"job", b}});
    EXPECT_EQ(wait_for_state(api, b, "planned").value("state", ""), "planned");
    EXPECT_EQ(wait_for_state(api, a, "planned").value("state", ""), "planned");
    api.call("queue.next");
    ASSERT_EQ(wait_for_state(api, a, "printing").value("state", ""), "printing");
    api.call("job.pause", {{"job", a}});  // on the cell whatever the load, then aborted
    ASSERT_EQ(wait_for_state(api, a, "paused").value("state", ""), "paused");
    api.call("job.abort", {{"job", a}});
    EXPECT_EQ(wait_for_state(api, a, "aborted").value("state", ""), "aborted");

    // The aborted part is on the bed and the queue waits for the operator's word.
    json q = api.call("queue.list");
    EXPECT_TRUE(q.value("paused", false)) << q.dump();
    EXPECT_THAT(q.value("paused_reason", ""), HasSubstr("aborted"));
    const Refusal on_bed = refusal([&] { api.call("queue.next"); });
    EXPECT_EQ(on_bed.code, api::errc::conflict);
    EXPECT_THAT(on_bed.message, HasSubstr("not clear"));
    q = api.call("cell.clear");
    EXPECT_TRUE(q.at("bed").at("clear").get<bool>());
    api.call("queue.resume");
    api.call("queue.next");
    ASSERT_TRUE(printed(wait_for_state(api, b, "completed", 120s)));
    const Refusal empty = refusal([&] { api.call("queue.next"); });
    EXPECT_EQ(empty.code, api::errc::conflict);
    EXPECT_THAT(empty.message, HasSubstr("empty"));
}

// A queue.json the service cannot read (a torn disk, a hand edit): it starts, keeps a copy, and
// holds every start until the operator has looked at the bed.
TEST_F(ServiceTest, AnUnreadableQueueFileLeavesTheCellNotClearUntilTheOperatorSaysSo) {
    fs::create_directories(state_dir());
    std::ofstream(state_dir() / "queue.json") << "{\"jobs\": [1, ";
    start_service(write_config());
    EXPECT_TRUE(service_->wait_for_log("queue.unreadable", 10s)) << service_->log();
    EXPECT_EQ(read_file(state_dir() / "queue.json.unreadable"), "{\"jobs\": [1, ");
    api::ApiClient api = client();
    json q = api.call("queue.list");
    EXPECT_FALSE(q.at("bed").at("clear").get<bool>()) << q.dump();
    const std::int64_t id = submit_bar(api, false);
    ASSERT_EQ(wait_for_state(api, id, "planned").value("state", ""), "planned");
    const Refusal held = refusal([&] { api.call("job.start", {{"job", id}}); });
    EXPECT_EQ(held.code, api::errc::conflict);
    EXPECT_THAT(held.message, HasSubstr("unreadable"));
    q = api.call("cell.clear");
    EXPECT_TRUE(q.at("bed").at("clear").get<bool>()) << q.dump();
    // The new file is whole again.
    EXPECT_TRUE(json::parse(read_file(state_dir() / "queue.json")).at("bed").at("clear").get<bool>());
}

}  // namespace service_queue_test
}  // namespace fibrecell::test
