// The robot I/O link (libmodbus client) against the simulated controller's Modbus server over real
// loopback TCP. Each test has its own server on an ephemeral port (the server binds port 0 itself
// and hands accepted sockets to libmodbus), so tests can run in parallel. Periods are short so that
// the whole file runs in a few seconds.
#include "drivers/abb/modbus/modbus_read_plan.hpp"
#include "drivers/abb/modbus/robot_io_config.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/sim/robot_io/robot_io_server.hpp"

#include "config/yaml_section.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/log_lines.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

using namespace fibrecell;
using namespace fibrecell::drivers::abb;
using fibrecell::drivers::sim::RobotIoServer;
using fibrecell::drivers::sim::RobotIoServerOptions;
using fibrecell::drivers::sim::ServiceCommands;
using namespace std::chrono_literals;
using ::testing::HasSubstr;
using fibrecell::test::eventually;
using fibrecell::test::LogLines;

namespace {

RobotIoConfig load(const std::string& yaml) {
    auto root = config::Section::load_text(yaml, "cell.yaml");
    auto c = load_robot_io_config(root.section("robot_io"));
    root.finish();
    return c;
}

std::string config_error(const std::string& yaml) {
    try {
        load(yaml);
    } catch (const config::ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

// Fast settings for a link to `server`.
RobotIoConfig fast_config(const RobotIoServer& server) {
    RobotIoConfig c;
    c.host = server.host();
    c.port = server.port();
    c.poll_period = 1ms;
    c.response_timeout = 200ms;
    c.heartbeat_period = 20ms;
    c.robot_heartbeat_timeout = 150ms;
    c.stable_reads = 1;
    c.reconnect_backoff_min = 20ms;
    c.reconnect_backoff_max = 160ms;
    return c;
}

RobotIoServerOptions fast_server() {
    RobotIoServerOptions o;
    o.robot_heartbeat_period = 20ms;
    return o;
}

// Records the link's state changes and events.
struct Recorder {
    std::mutex mu;
    std::vector<RobotIoStateChange> states;
    std::vector<EventCounterChange> events;

    void attach(RobotIoLink& link) {
        link.on_state([this](const RobotIoStateChange& c) {
            std::lock_guard lock(mu);
            states.push_back(c);
        });
        link.on_event([this](const EventCounterChange& e) {
            std::lock_guard lock(mu);
            events.push_back(e);
        });
    }
    std::vector<RobotIoStateChange> state_log() {
        std::lock_guard lock(mu);
        return states;
    }
    std::vector<EventCounterChange> event_log() {
        std::lock_guard lock(mu);
        return events;
    }
    // The first transition into `to` at or after index `from`, if any.
    std::optional<RobotIoStateChange> find(RobotIoState to, std::size_t from = 0) {
        std::lock_guard lock(mu);
        for (std::size_t i = from; i < states.size(); ++i)
            if (states[i].to == to) return states[i];
        return std::nullopt;
    }
};

// A link that is up with the robot heartbeat seen.
void bring_up(RobotIoLink& link) {
    link.start();
    ASSERT_TRUE(link.wait_until_up(3000ms)) << link.snapshot().last_error;
    ASSERT_TRUE(eventually([&] { return link.snapshot().robot_heartbeat_ok; }));
}

}  // namespace

// --- configuration -----------------------------------------------------------------------------

TEST(RobotIoConfig, DefaultsAreTheDocumentedMap) {
    const RobotIoConfig c = load("robot_io: {}\n");
    EXPECT_EQ(c.port, 502);
    EXPECT_EQ(c.unit_id, 1);
    EXPECT_EQ(c.poll_period, 2ms);
    EXPECT_EQ(c.heartbeat_period, 100ms);
    EXPECT_EQ(c.robot_heartbeat_timeout, 1000ms);
    EXPECT_EQ(c.stable_reads, 2);
    EXPECT_EQ(describe(c.map.event_number), "input register 0");
    EXPECT_EQ(describe(c.map.barrier_number), "input register 1");
    EXPECT_EQ(describe(c.map.robot_running), "discrete input 32");
    EXPECT_EQ(describe(c.map.heartbeat_in), "discrete input 33");
    EXPECT_EQ(describe(c.map.barrier_release), "holding register 0");
    EXPECT_EQ(describe(c.map.pause_request), "coil 16");
    EXPECT_EQ(describe(c.map.abort_request), "coil 17");
    EXPECT_EQ(describe(c.map.heartbeat_out), "coil 18");
    EXPECT_FALSE(c.map.chunk_ready);
    // One read request per table: input registers 0..1 and discrete inputs 32..33.
    const ReadPlan plan = make_read_plan(c.map);
    ASSERT_EQ(plan.blocks.size(), 2u);
    EXPECT_EQ(describe_block(plan.blocks[0]), "discrete inputs 32..33");
    EXPECT_EQ(describe_block(plan.blocks[1]), "input registers 0..1");
}

TEST(RobotIoConfig, ReadsEveryKey) {
    const RobotIoConfig c = load(R"(
robot_io:
  host: 192.168.125.50
  port: 1502
  unit_id: 255
  poll_period_ms: 0.5
  response_timeout_ms: 50
  heartbeat_period_ms: 50
  robot_heartbeat_timeout_ms: 400
  stable_reads: 1
  reconnect_backoff_min_ms: 10
  reconnect_backoff_max_ms: 2000
  pause_on_fault: false
  service_watchdog_ms: 300
  stats_log_period_s: 0
  map:
    heartbeat_in: {table: input_register, address: 2, bit: 1}
    robot_running: {table: input_register, address: 2, bit: 0}
    chunk_ready: {address: 2}
)");
    EXPECT_EQ(c.host, "192.168.125.50");
    EXPECT_EQ(c.port, 1502);
    EXPECT_EQ(c.unit_id, 255);
    EXPECT_EQ(c.poll_period, 500us);
    EXPECT_EQ(c.response_timeout, 50ms);
    EXPECT_EQ(c.robot_heartbeat_timeout, 400ms);
    EXPECT_EQ(c.stable_reads, 1);
    EXPECT_EQ(c.reconnect_backoff_max, 2000ms);
    EXPECT_FALSE(c.pause_on_fault);
    EXPECT_EQ(c.service_watchdog, 300ms);
    EXPECT_EQ(describe(c.map.heartbeat_in), "input register 2 bit 1");
    ASSERT_TRUE(c.map.chunk_ready);
    EXPECT_EQ(describe(*c.map.chunk_ready), "holding register 2");
    // Bits inside input register 2 join the event and barrier registers in one request.
    const ReadPlan plan = make_read_plan(c.map);
    ASSERT_EQ(plan.blocks.size(), 1u);
    EXPECT_EQ(describe_block(plan.blocks[0]), "input registers 0..2");
}

TEST(RobotIoConfig, ErrorsNameTheKey) {
    EXPECT_THAT(config_error("robot_io:\n  poll_period: 2\n"),
                HasSubstr("robot_io.poll_period: unknown key"));
    EXPECT_THAT(config_error("robot_io:\n  port: 70000\n"),
                HasSubstr("line 2: robot_io.port: must be in [1, 65535], got 70000"));
    EXPECT_THAT(config_error("robot_io:\n  unit_id: 250\n"),
                HasSubstr("robot_io.unit_id: must be in [0, 247] or 255"));
    EXPECT_THAT(config_error("robot_io:\n  reconnect_backoff_max_ms: 50\n"),
                HasSubstr("robot_io.reconnect_backoff_max_ms: must be at least"));
    EXPECT_THAT(
        config_error("robot_io:\n  robot_heartbeat_timeout_ms: 10\n  poll_period_ms: 20\n"),
        HasSubstr("robot_io.robot_heartbeat_timeout_ms: must be longer than poll_period_ms"));
    EXPECT_THAT(config_error("robot_io:\n  map:\n    pause_request: {table: coil, adress: 3}\n"),
                HasSubstr("robot_io.map.pause_request.address: is required"));
    EXPECT_THAT(config_error("robot_io:\n  map:\n    pause_request: {address: 3, colour: red}\n"),
                HasSubstr("robot_io.map.pause_request.colour: unknown key"));
    EXPECT_THAT(
        config_error("robot_io:\n  map:\n    pause_request: {table: discrete_input, address: 3}\n"),
        HasSubstr("robot_io.map.pause_request: table 'discrete_input' cannot carry this "
                  "signal: use coil"));
    EXPECT_THAT(config_error("robot_io:\n  map:\n    event_number: {table: coil, address: 3}\n"),
                HasSubstr("robot_io.map.event_number: table 'coil' cannot carry"));
    EXPECT_THAT(config_error("robot_io:\n  map:\n    abort_request: {address: 16}\n"),
                HasSubstr("robot_io.map.abort_request: coil 16 is already used by pause_request"));
    EXPECT_THAT(
        config_error(
            "robot_io:\n  map:\n    heartbeat_in: {table: input_register, address: 2, bit: 16}\n"),
        HasSubstr("robot_io.map.heartbeat_in.bit: must be in [0, 15]"));
    EXPECT_THAT(config_error("robot_io:\n  map:\n    flow: {table: coil, address: 3}\n"),
                HasSubstr("robot_io.map.flow: unknown key"));
    EXPECT_THAT(config_error("robot_io:\n  pause_on_fault: maybe\n"),
                HasSubstr("robot_io.pause_on_fault: must be true or false"));
}

TEST(RobotIoConfig, CodeBuiltConfigIsValidatedToo) {
    RobotIoConfig c;
    c.map.heartbeat_out = c.map.pause_request;
    EXPECT_THROW(RobotIoLink{c}, std::invalid_argument);
    EXPECT_THROW(RobotIoServer{c.map}, std::invalid_argument);
}

// --- link against the server -------------------------------------------------------------------

TEST(RobotIoLink, EventCounterChangesArriveInOrderWithTimestamps) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(fast_config(server));
    rec.attach(link);
    bring_up(link);
    EXPECT_EQ(link.state(), RobotIoState::up);

    std::vector<std::chrono::steady_clock::time_point> set_at;
    for (std::uint16_t n = 1; n <= 40; ++n) {
        set_at.push_back(std::chrono::steady_clock::now());
        server.set_barrier_number(n / 10);
        server.set_event_number(n);
        // Longer than a poll, so that every value is seen (the sync engine catches up otherwise).
        ASSERT_TRUE(eventually([&] { return link.snapshot().event_counter == n; }));
    }
    const auto events = rec.event_log();
    ASSERT_FALSE(events.empty());
    EXPECT_FALSE(events.front().previous);  // the first value after start()
    EXPECT_EQ(events.front().value, 0);
    ASSERT_EQ(events.size(), 41u);
    for (std::size_t i = 1; i < events.size(); ++i) {
        const auto& e = events[i];
        EXPECT_EQ(e.value, i);
        ASSERT_TRUE(e.previous);
        EXPECT_EQ(*e.previous, i - 1);
        EXPECT_EQ(e.barrier, i / 10);
        EXPECT_LE(e.first_read, e.accepted);
        EXPECT_GE(e.first_read, set_at[i - 1]);  // never before the robot changed it
        EXPECT_GE(e.accepted, events[i - 1].accepted);
    }
    // The same changes are queued for a consumer on another thread.
    const auto queued = link.take_events();
    ASSERT_EQ(queued.size(), events.size());
    EXPECT_EQ(queued.back().value, 40);
    EXPECT_TRUE(link.take_events().empty());
    EXPECT_EQ(link.snapshot().stats.event_changes, 41u);
}

TEST(RobotIoLink, StableReadsFilterTornValues) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    RobotIoConfig c = fast_config(server);
    c.stable_reads = 2;
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(c);
    rec.attach(link);
    bring_up(link);
    server.set_event_number(6);
    ASSERT_TRUE(eventually([&] { return link.snapshot().event_counter == 6; }));
    // A torn value read once is dropped; the true value counts once two polls agree.
    server.inject_torn_event_reads(0x00FF, 1);
    ASSERT_TRUE(eventually([&] { return link.snapshot().stats.torn_reads >= 1; }));
    server.set_event_number(7);
    ASSERT_TRUE(eventually([&] { return link.snapshot().event_counter == 7; }));
    // Read twice in a row, even a wrong value counts (raise stable_reads for slower filters).
    // It stands for two polls only (2 ms) before the true value is back: the change log says it
    // counted, where a look at the snapshot on a busy machine can miss it.
    server.inject_torn_event_reads(0x0100, 2);
    ASSERT_TRUE(eventually([&] {
        const auto log = rec.event_log();
        return log.size() >= 5 && log[3].value == 0x0100 && log[4].value == 7;
    }));
    EXPECT_EQ(link.snapshot().event_counter, 7);
    std::vector<std::uint16_t> values;
    for (const auto& e : rec.event_log()) values.push_back(e.value);
    EXPECT_THAT(values, ::testing::ElementsAre(0, 6, 7, 0x0100, 7));
    const auto last = rec.event_log().back();
    EXPECT_LT(last.first_read, last.accepted);  // read by an earlier poll than the accepting one
}

TEST(RobotIoLink, OutputsReachTheServer) {
    RobotIoMap map;
    map.chunk_ready = ModbusAddress{ModbusTable::holding_register, 2, std::nullopt};
    RobotIoServer server(map, fast_server());
    RobotIoConfig c = fast_config(server);
    c.map = map;
    RobotIoLink link(c);
    bring_up(link);
    link.set_release(17);
    link.set_pause(true);
    link.set_abort(true);
    link.set_chunk_ready(4);
    EXPECT_TRUE(server.wait_for_commands(
        [](const ServiceCommands& s) {
            return s.release == 17 && s.pause && s.abort && s.chunk_ready == 4;
        },
        1000ms));
    link.set_pause(false);
    link.set_abort(false);
    link.set_release(18);
    EXPECT_TRUE(server.wait_for_commands(
        [](const ServiceCommands& s) { return s.release == 18 && !s.pause && !s.abort; }, 1000ms));
    const auto snap = link.snapshot();
    EXPECT_EQ(snap.outputs.release, 18);
    EXPECT_EQ(snap.outputs.chunk_ready, 4);
    EXPECT_GE(snap.stats.writes, 5u);
}

TEST(RobotIoLink, ChunkReadyNeedsAMappedAddress) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    RobotIoLink link(fast_config(server));
    try {
        link.set_chunk_ready(3);
        FAIL() << "expected an error";
    } catch (const RobotIoError& e) {
        EXPECT_THAT(e.what(), HasSubstr("robot_io.map.chunk_ready is not configured"));
    }
}

TEST(RobotIoLink, ServiceHeartbeatTogglesAtItsPeriod) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    RobotIoLink link(fast_config(server));
    bring_up(link);
    const auto first = server.commands();
    ASSERT_TRUE(server.wait_for_commands(
        [&](const ServiceCommands& s) { return s.heartbeat_edges >= first.heartbeat_edges + 10; },
        2000ms));
    const auto last = server.commands();
    const double period_ms = std::chrono::duration<double, std::milli>(last.last_heartbeat_edge -
                                                                       first.last_heartbeat_edge)
                                 .count() /
                             static_cast<double>(last.heartbeat_edges - first.heartbeat_edges);
    EXPECT_NEAR(period_ms, 20.0, 5.0);
}

TEST(RobotIoLink, ServiceHeartbeatStopsWhenTheServiceLoopStalls) {
    const LogLines log;  // before the link's thread logs
    RobotIoServer server(RobotIoMap{}, fast_server());
    RobotIoConfig c = fast_config(server);
    c.service_watchdog = 100ms;
    RobotIoLink link(c);
    link.service_alive();
    bring_up(link);
    std::atomic<bool> feeding{true};
    std::thread loop([&] {
        while (feeding) {
            link.service_alive();
            std::this_thread::sleep_for(5ms);
        }
    });
    const auto before = server.commands().heartbeat_edges;
    EXPECT_TRUE(server.wait_for_commands(
        [&](const ServiceCommands& s) { return s.heartbeat_edges >= before + 3; }, 1000ms));
    feeding = false;
    loop.join();
    // The watchdog runs out: the link says so when it skips the toggle.
    ASSERT_TRUE(log.wait_for("robot_io.service_stalled"));
    const auto stalled = server.commands().heartbeat_edges;
    // Five heartbeat periods of the link's own polling later (a poll every 1 ms at the most
    // often), it still has not toggled.
    const auto polls = link.snapshot().stats.polls;
    ASSERT_TRUE(eventually([&] { return link.snapshot().stats.polls >= polls + 100; }));
    EXPECT_EQ(server.commands().heartbeat_edges, stalled);
    link.service_alive();
    EXPECT_TRUE(server.wait_for_commands(
        [&](const ServiceCommands& s) { return s.heartbeat_edges > stalled; }, 1000ms));
}

TEST(RobotIoLink, RobotHeartbeatLostIsAFaultWithTheReason) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(fast_config(server));
    rec.attach(link);
    bring_up(link);
    const std::size_t mark = rec.state_log().size();
    const auto t0 = std::chrono::steady_clock::now();
    server.set_robot_heartbeat_running(false);
    ASSERT_TRUE(eventually([&] { return rec.find(RobotIoState::fault, mark).has_value(); }));
    const auto fault = *rec.find(RobotIoState::fault, mark);
    EXPECT_EQ(fault.from, RobotIoState::up);
    EXPECT_THAT(fault.reason, ::testing::MatchesRegex("robot heartbeat lost for [0-9]+ ms"));
    const std::string prefix = "robot heartbeat lost for ";
    ASSERT_EQ(fault.reason.rfind(prefix, 0), 0u) << fault.reason;
    EXPECT_GE(std::stoi(fault.reason.substr(prefix.size())), 150);
    EXPECT_GE(fault.at - t0, 130ms);
    const auto snap = link.snapshot();
    EXPECT_EQ(snap.state, RobotIoState::fault);
    EXPECT_EQ(snap.fault_reason, fault.reason);
    EXPECT_FALSE(snap.robot_heartbeat_ok);
    EXPECT_TRUE(snap.connected);  // the coupler is fine: nothing to reconnect
    // The link asks the robot to pause on every fault (pause_on_fault).
    EXPECT_TRUE(server.wait_for_commands([](const ServiceCommands& s) { return s.pause; }, 1000ms));
    EXPECT_TRUE(snap.outputs.pause);

    server.set_robot_heartbeat_running(true);
    ASSERT_TRUE(link.wait_until_up(1000ms));
    // The callback runs just after the snapshot shows the state.
    ASSERT_TRUE(eventually([&] { return rec.find(RobotIoState::up, mark).has_value(); }));
    const auto up = rec.find(RobotIoState::up, mark);
    EXPECT_THAT(up->reason, HasSubstr("recovered after"));
    // Resuming is the service's decision: the pause request stays until it clears it.
    EXPECT_TRUE(server.commands().pause);
    link.set_pause(false);
    EXPECT_TRUE(
        server.wait_for_commands([](const ServiceCommands& s) { return !s.pause; }, 1000ms));
    EXPECT_EQ(link.snapshot().stats.faults, 1u);
}

TEST(RobotIoLink, DroppedConnectionIsAFaultThenReconnectsAndRecovers) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(fast_config(server));
    rec.attach(link);
    bring_up(link);
    server.set_event_number(3);
    ASSERT_TRUE(eventually([&] { return link.snapshot().event_counter == 3; }));
    const std::size_t mark = rec.state_log().size();
    server.drop_connections();
    ASSERT_TRUE(eventually([&] { return rec.find(RobotIoState::fault, mark).has_value(); }));
    const auto fault = *rec.find(RobotIoState::fault, mark);
    EXPECT_THAT(fault.reason, HasSubstr("modbus 127.0.0.1:" + std::to_string(server.port()) +
                                        ": connection lost ("));
    // The robot went on while the link was down: the change arrives after the reconnect.
    server.set_event_number(4);
    ASSERT_TRUE(link.wait_until_up(2000ms)) << link.snapshot().last_error;
    // The callback runs just after the snapshot shows the state.
    ASSERT_TRUE(eventually([&] { return rec.find(RobotIoState::up, mark).has_value(); }));
    const auto up = rec.find(RobotIoState::up, mark);
    EXPECT_THAT(up->reason, HasSubstr("recovered after"));
    EXPECT_TRUE(eventually([&] { return link.snapshot().event_counter == 4; }));
    const auto events = rec.event_log();
    ASSERT_GE(events.size(), 2u);
    EXPECT_EQ(events.back().value, 4);
    EXPECT_EQ(events.back().previous, std::optional<std::uint16_t>(3));
    const auto snap = link.snapshot();
    EXPECT_TRUE(snap.connected);
    EXPECT_TRUE(snap.robot_heartbeat_ok);
    EXPECT_EQ(snap.stats.connects, 2u);
    EXPECT_EQ(snap.stats.faults, 1u);
    // The pause request set by the fault was written on the new connection.
    EXPECT_TRUE(server.wait_for_commands([](const ServiceCommands& s) { return s.pause; }, 1000ms));
    EXPECT_EQ(server.stats().connections_open, 1u);
}

TEST(RobotIoLink, RefusedConnectionsAreRetriedWithBackOff) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(fast_config(server));
    rec.attach(link);
    bring_up(link);
    const auto t0 = std::chrono::steady_clock::now();
    server.refuse_connections_for(400ms);
    server.drop_connections();
    ASSERT_TRUE(eventually([&] { return link.state() == RobotIoState::fault; }));
    ASSERT_TRUE(eventually(
        [&] { return link.snapshot().last_error.find("connect failed") != std::string::npos; }));
    EXPECT_THAT(link.snapshot().last_error,
                HasSubstr("modbus 127.0.0.1:" + std::to_string(server.port()) +
                          ": connect failed (Connection refused)"));
    ASSERT_TRUE(link.wait_until_up(3000ms)) << link.snapshot().last_error;
    EXPECT_GE(std::chrono::steady_clock::now() - t0, 400ms);
    const auto snap = link.snapshot();
    // Back-off 20, 40, 80, 160, 160 ms: a handful of attempts in 400 ms, not hundreds.
    EXPECT_GE(snap.stats.connect_failures, 2u);
    EXPECT_LE(snap.stats.connect_failures, 8u);
    EXPECT_EQ(snap.fault_reason, "");
}

TEST(RobotIoLink, UnansweredRequestsTimeOut) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(fast_config(server));
    rec.attach(link);
    bring_up(link);
    const std::size_t mark = rec.state_log().size();
    server.set_answering(false);
    ASSERT_TRUE(eventually([&] { return rec.find(RobotIoState::fault, mark).has_value(); }));
    EXPECT_THAT(rec.find(RobotIoState::fault, mark)->reason,
                ::testing::MatchesRegex(".*: no response to .* within 200 ms \\(.*\\)"));
    server.set_answering(true);
    ASSERT_TRUE(link.wait_until_up(3000ms)) << link.snapshot().last_error;
}

TEST(RobotIoLink, StaysConnectingUntilTheCouplerAnswers) {
    RobotIoServer server(RobotIoMap{}, fast_server());
    server.refuse_connections_for(200ms);
    Recorder rec;  // outlives the link that calls it
    RobotIoLink link(fast_config(server));
    rec.attach(link);
    link.start();
    ASSERT_TRUE(eventually([&] { return !link.snapshot().last_error.empty(); }));
    EXPECT_EQ(link.state(), RobotIoState::connecting);  // never up yet: not a fault
    EXPECT_THAT(link.snapshot().last_error, HasSubstr("connect failed (Connection refused)"));
    ASSERT_TRUE(link.wait_until_up(3000ms));
    EXPECT_FALSE(rec.find(RobotIoState::fault));
    EXPECT_EQ(link.snapshot().stats.faults, 0u);
}

TEST(RobotIoLink, ReadsRobotBitsFromTheRegisterViewOfATwoViewCoupler) {
    RobotIoServer server(RobotIoMap{}, fast_server());  // serves DIs 32-33 = IR 2 bits 0-1 too
    RobotIoConfig c = fast_config(server);
    c.map.robot_running = ModbusAddress{ModbusTable::input_register, 2, 0};
    c.map.heartbeat_in = ModbusAddress{ModbusTable::input_register, 2, 1};
    RobotIoLink link(c);
    bring_up(link);
    EXPECT_FALSE(link.snapshot().running);
    server.set_running(true);
    EXPECT_TRUE(eventually([&] { return link.snapshot().running; }));
    // One request per poll cycle (plus the writes).
    EXPECT_EQ(make_read_plan(c.map).blocks.size(), 1u);
}

TEST(RobotIoLink, StartStopAndDestroyAreClean) {
    auto server = std::make_unique<RobotIoServer>(RobotIoMap{}, fast_server());
    RobotIoLink link(fast_config(*server));
    for (int i = 0; i < 3; ++i) {
        link.start();
        link.start();  // idempotent
        ASSERT_TRUE(link.wait_until_up(2000ms));
        link.stop();
        EXPECT_EQ(link.state(), RobotIoState::stopped);
        link.stop();
    }
    link.start();
    ASSERT_TRUE(link.wait_until_up(2000ms));
    server.reset();  // the coupler goes away under a running link
    ASSERT_TRUE(eventually([&] { return link.state() == RobotIoState::fault; }));
    const auto t0 = std::chrono::steady_clock::now();
    link.stop();
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 500ms);
}
