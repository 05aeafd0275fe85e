#pragma once
// Data the controller predefines (docs/rapid-subset.md, "Predefined data", which also explains
// the [S]/[K] marks): tool0, wobj0, load0, the speeds v5 ... v7000 and vmax, the zones fine,
// z0 ... z200, and a few constants (pi, diskhome). A module may use them without declaring them
// and must not redeclare them.

#include <string_view>

#include "drivers/abb/rapid/value.hpp"

namespace fibrecell::drivers::abb::rapid {

struct PredefinedData {
    std::string_view type;  // "speeddata", "tooldata", ...
    bool constant = true;   // CONST in the system (speeds, zones, pi); tool0/wobj0/load0 are PERS
    Value value;            // typed (conform()ed) value
};

// Case-insensitive; nullptr for a name the system does not predefine. The data lives for the
// whole program.
const PredefinedData* predefined_data(std::string_view name);
bool is_predefined_data(std::string_view name);

}  // namespace fibrecell::drivers::abb::rapid
