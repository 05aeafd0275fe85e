#pragma once
// The spacing W between fibre paths [mm] (the paper's symbol) that the fibre tests plan at.

namespace fibrecell::test {

inline constexpr double W = 1.0;

}  // namespace fibrecell::test
