#include "daemon/history/history_config.hpp"

namespace fibrecell::daemon::history {

HistoryConfig load_history_config(config::Section s) {
    HistoryConfig c;
    c.keep = s.integer("keep", c.keep, 1, 1'000'000);
    c.keep_days = s.integer("keep_days", c.keep_days, 0, 100'000);
    c.prune_plans = s.get_or<bool>("prune_plans", c.prune_plans);
    s.finish();
    return c;
}

}  // namespace fibrecell::daemon::history
