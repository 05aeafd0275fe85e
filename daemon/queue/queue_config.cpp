#include "daemon/queue/queue_config.hpp"

namespace fibrecell::daemon::queue {

const char* to_string(AutoStart a) { return a == AutoStart::after_clear ? "after_clear" : "manual"; }

QueueConfig load_queue_config(config::Section s) {
    QueueConfig c;
    c.auto_start = s.choice("auto_start", "manual", {"manual", "after_clear"}) == "after_clear"
                       ? AutoStart::after_clear
                       : AutoStart::manual;
    s.finish();
    return c;
}

}  // namespace fibrecell::daemon::queue
