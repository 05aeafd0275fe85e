// Sync faults in a real small cell (sync_test_cell.hpp): the robot's counter going back, the
// board unplugged in the middle of a fibre path, the robot I/O connection lost. Each ends in one
// fault with a reason, the robot asked to pause, and the last confirmed event kept for a resume.
#include "sync_test_cell.hpp"

#include <gmock/gmock.h>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

class SyncFaultTest : public SyncCellTest {
  protected:
    void expect_one_fault_containing(const std::string& text) {
        ASSERT_TRUE(eventually([&] { return engine_->status().faulted; }));
        const SyncStatus s = engine_->status();
        EXPECT_THAT(s.fault_reason, HasSubstr(text));
        EXPECT_TRUE(server_->wait_for_commands([](const auto& c) { return c.pause; }, 5s));
        std::this_thread::sleep_for(20ms);
        EXPECT_THAT(faults(), ElementsAre(s.fault_reason));
    }
};

TEST_F(SyncFaultTest, TheCounterGoingBackIsAFault) {
    boot();
    start_engine();
    robot_at(1);
    server_->set_event_number(2);
    server_->set_event_number(3);  // extrude_off: the PLA feed stops
    ASSERT_TRUE(eventually([&] { return engine_->status().last_confirmed == 3; }));
    server_->set_event_number(2);
    expect_one_fault_containing("robot event counter went back from event 3 to 2");
    const auto board_lines = executed_job().size();
    server_->set_event_number(4);  // ignored after a fault
    std::this_thread::sleep_for(50ms);
    const SyncStatus s = engine_->status();
    EXPECT_EQ(s.last_confirmed, 3);
    EXPECT_EQ(s.last_received, 3);
    // M108 (the abort) is the only thing the board may still have run.
    const auto log = executed_job();
    ASSERT_GE(log.size(), board_lines);
    for (std::size_t i = board_lines; i < log.size(); ++i) EXPECT_EQ(log[i], "M108");
}

TEST_F(SyncFaultTest, TheBoardUnpluggedMidPathIsAFault) {
    boot();
    start_engine();
    for (int n = 1; n <= 5; ++n) {
        robot_at(n);
        if (n == 2) {  // let the PLA metering finish
            ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_sent == 40; }));
        }
    }
    robot_at(6);
    ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_sent >= 5; }));
    mock_->unplug();
    expect_one_fault_containing("extruder board: link_lost: serial");
    const SyncStatus s = engine_->status();
    EXPECT_EQ(s.last_confirmed, 6);
    EXPECT_FALSE(s.metering.active);
}

TEST_F(SyncFaultTest, TheRobotIoConnectionLostIsAFault) {
    boot();
    start_engine();
    robot_at(1);
    server_->refuse_connections_for(1s);
    server_->drop_connections();
    expect_one_fault_containing("robot I/O: modbus 127.0.0.1:");
    EXPECT_EQ(engine_->status().last_confirmed, 1);
}
