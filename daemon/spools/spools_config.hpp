#pragma once
// The `spools:` section of the cell YAML: what a start or a queueing does when the loaded spools
// hold less than the job needs (docs/spools.md).
//
//   spools:
//     check: refuse        # refuse: the start or queue.add is refused with the figures
//                          # warn: it goes ahead, with a warning in the log; off: no check
//     margin_percent: 5    # needed = what the plan feeds (less what the job fed already)
//     margin_m: 0.5        #          * (1 + margin_percent/100) + margin_m

#include "config/yaml_section.hpp"

namespace fibrecell::daemon::spools {

enum class SpoolCheck { refuse, warn, off };

struct SpoolsConfig {
    SpoolCheck check = SpoolCheck::refuse;
    double margin_percent = 5;
    double margin_m = 0.5;
};

const char* to_string(SpoolCheck c);

// Throws config::ConfigError naming the key ("spools.check").
SpoolsConfig load_spools_config(config::Section s);

}  // namespace fibrecell::daemon::spools
