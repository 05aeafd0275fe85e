#include "daemon/spools/spools_config.hpp"

namespace fibrecell::daemon::spools {

const char* to_string(SpoolCheck c) {
    switch (c) {
        case SpoolCheck::refuse: return "refuse";
        case SpoolCheck::warn: return "warn";
        case SpoolCheck::off: return "off";
    }
    return "?";
}

SpoolsConfig load_spools_config(config::Section s) {
    SpoolsConfig c;
    const std::string check = s.choice("check", "refuse", {"refuse", "warn", "off"});
    c.check = check == "warn" ? SpoolCheck::warn : check == "off" ? SpoolCheck::off : SpoolCheck::refuse;
    c.margin_percent = s.number("margin_percent", c.margin_percent, 0, 100);
    c.margin_m = s.number("margin_m", c.margin_m, 0, 10000);
    s.finish();
    return c;
}

}  // namespace fibrecell::daemon::spools
