#include "daemon/cell/part_limits.hpp"

#include <string>

namespace fibrecell::daemon {

PartLimits load_part_limits(config::Section s) {
    PartLimits l;
    l.max_size_mm = s.vec3_or("max_size_mm", l.max_size_mm);
    for (std::size_t i = 0; i < 3; ++i)
        if (!(l.max_size_mm[i] > 0 && l.max_size_mm[i] <= 5000))
            s.fail("max_size_mm", "each size must be in (0, 5000] mm, got " +
                                      std::to_string(l.max_size_mm[i]));
    l.max_layers = s.integer("max_layers", l.max_layers, 1, 100000);
    l.max_tets = s.integer("max_tets", l.max_tets, 1, 10'000'000);
    s.finish();
    return l;
}

}  // namespace fibrecell::daemon
