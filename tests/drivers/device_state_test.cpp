#include "drivers/device_state.hpp"

#include <gtest/gtest.h>

#include <map>
#include <utility>

using namespace fibrecell::drivers;

// Walks every (state, event) pair: the allowed ones land where the table says, the rest refuse.
TEST(DeviceState, EveryTransitionAllowedOrRefused) {
    using S = DeviceState;
    using E = DeviceEvent;
    const std::map<std::pair<S, E>, S> allowed = {
        {{S::unconfigured, E::configure}, S::inactive}, {{S::inactive, E::activate}, S::active},
        {{S::inactive, E::reset}, S::unconfigured},     {{S::inactive, E::fault}, S::error},
        {{S::active, E::deactivate}, S::inactive},      {{S::active, E::fault}, S::error},
        {{S::error, E::clear}, S::unconfigured},
    };
    for (S s : {S::unconfigured, S::inactive, S::active, S::error}) {
        for (E e : {E::configure, E::activate, E::deactivate, E::fault, E::clear, E::reset}) {
            const auto got = next_state(s, e);
            const auto it = allowed.find({s, e});
            if (it == allowed.end()) {
                EXPECT_FALSE(got) << to_string(s) << " + " << to_string(e) << " must be refused";
            } else {
                ASSERT_TRUE(got) << to_string(s) << " + " << to_string(e) << " must be allowed";
                EXPECT_EQ(*got, it->second);
            }
        }
    }
}
