#include "daemon/sync/sync_status.hpp"

namespace fibrecell::daemon::sync {

std::string_view to_string(ShortfallKind k) {
    switch (k) {
        case ShortfallKind::fibre_feed_dropped: return "fibre_feed_dropped";
        case ShortfallKind::pla_feed_dropped: return "pla_feed_dropped";
        case ShortfallKind::late_cut: return "late_cut";
    }
    return "unknown";
}

}  // namespace fibrecell::daemon::sync
