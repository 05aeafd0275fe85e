#include "drivers/abb/modbus/modbus_read_plan.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace fibrecell::drivers::abb {
namespace {

// Largest reads the protocol allows (FC 3/4: 125 registers, FC 1/2: 2000 bits).
int max_count(ModbusTable t) {
    return is_bit_table(t) ? 2000 : 125;
}

}  // namespace

ReadPlan make_read_plan(const RobotIoMap& map) {
    std::map<ModbusTable, std::set<int>> wanted;
    for (const ModbusAddress* a :
         {&map.event_number, &map.barrier_number, &map.robot_running, &map.heartbeat_in})
        wanted[a->table].insert(a->address);
    ReadPlan plan;
    for (const auto& [table, addresses] : wanted) {
        ReadBlock b{table, -1, 0};
        for (int a : addresses) {
            if (b.count > 0 && a == b.start + b.count && b.count < max_count(table)) {
                ++b.count;
                continue;
            }
            if (b.count > 0) plan.blocks.push_back(b);
            b = ReadBlock{table, a, 1};
        }
        if (b.count > 0) plan.blocks.push_back(b);
    }
    return plan;
}

std::string describe_block(const ReadBlock& b) {
    std::string t(to_string(b.table));
    std::replace(t.begin(), t.end(), '_', ' ');
    if (b.count == 1) return t + " " + std::to_string(b.start);
    return t + "s " + std::to_string(b.start) + ".." + std::to_string(b.start + b.count - 1);
}

InputBuffers::InputBuffers(const ReadPlan& plan) {
    for (const auto& b : plan.blocks) {
        const bool bits_block = is_bit_table(b.table);
        words.emplace_back(bits_block ? 0 : b.count);
        bits.emplace_back(bits_block ? b.count : 0);
    }
}

namespace {
// The block holding `a` and the offset in it.
std::pair<std::size_t, std::size_t> locate(const ReadPlan& plan, const ModbusAddress& a) {
    for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
        const auto& b = plan.blocks[i];
        if (b.table == a.table && a.address >= b.start && a.address < b.start + b.count)
            return {i, static_cast<std::size_t>(a.address - b.start)};
    }
    throw std::logic_error("robot_io: " + describe(a) + " is not in the read plan");
}
}  // namespace

std::uint16_t InputBuffers::word(const ReadPlan& plan, const ModbusAddress& a) const {
    const auto [i, off] = locate(plan, a);
    return words[i][off];
}

bool InputBuffers::bit(const ReadPlan& plan, const ModbusAddress& a) const {
    const auto [i, off] = locate(plan, a);
    if (is_bit_table(a.table)) return bits[i][off] != 0;
    return ((words[i][off] >> a.bit.value_or(0)) & 1u) != 0;
}

}  // namespace fibrecell::drivers::abb
