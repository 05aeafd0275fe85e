#pragma once
// The pure built-in functions evaluate() computes: maths (degrees), rounding, string helpers,
// Offs and OrientZYX. Functions that read I/O or robot state are the simulator's (EvalContext).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/value.hpp"

namespace fibrecell::drivers::abb::rapid {

struct NamedValue {
    std::string name;            // optional argument or switch name, as written
    std::optional<Value> value;  // absent for a switch
};

struct BuiltinArgs {
    std::vector<Value> positional;
    std::vector<NamedValue> optional;
};

// Throws EvalError (evaluate.hpp) on wrong arguments or a function it does not compute.
Value call_builtin(std::string_view name, const BuiltinArgs& args, std::size_t line);

}  // namespace fibrecell::drivers::abb::rapid
