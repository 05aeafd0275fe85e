#pragma once
// The requests one poll makes: the robot -> service signals grouped, per table, into runs of
// consecutive addresses, one read request each (the default map: input registers 0-1 and discrete
// inputs 32-33). Only consecutive addresses are merged, so that a poll never asks for an address
// the coupler may not have.

#include "drivers/abb/modbus/robot_io_config.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace fibrecell::drivers::abb {

struct ReadBlock {
    ModbusTable table = ModbusTable::input_register;
    int start = 0;  // first address
    int count = 0;  // registers or bits
};

struct ReadPlan {
    std::vector<ReadBlock> blocks;
};

// Blocks for event_number, barrier_number, robot_running and heartbeat_in.
ReadPlan make_read_plan(const RobotIoMap& map);

// "input registers 0..1", "discrete input 32".
std::string describe_block(const ReadBlock& b);

// One buffer per block, filled by the reads; decodes signals from them.
struct InputBuffers {
    explicit InputBuffers(const ReadPlan& plan);
    std::vector<std::vector<std::uint16_t>> words;  // register blocks
    std::vector<std::vector<std::uint8_t>> bits;    // bit blocks (one byte per bit)

    std::uint16_t word(const ReadPlan& plan, const ModbusAddress& a) const;
    bool bit(const ReadPlan& plan, const ModbusAddress& a) const;
};

}  // namespace fibrecell::drivers::abb
