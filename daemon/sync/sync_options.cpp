#include "daemon/sync/sync_options.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fibrecell::daemon::sync {
namespace {

void require_positive(double v, const char* field) {
    if (!(v > 0) || !std::isfinite(v))
        throw std::invalid_argument(std::string("sync: ") + field + " must be positive, got " +
                                    std::to_string(v));
}

}  // namespace

double effective_lead_s(const SyncOptions& options) {
    return std::max(options.lead_s, options.min_lead_real_s * options.time_scale);
}

void validate(const SyncOptions& o, std::int64_t events_total) {
    require_positive(o.hotends.pla_c, "hotends.pla_c");
    require_positive(o.hotends.ccf_c, "hotends.ccf_c");
    require_positive(o.pla_line_width_mm, "pla_line_width_mm");
    require_positive(o.pla_layer_height_mm, "pla_layer_height_mm");
    require_positive(o.temp_window_c, "temp_window_c");
    require_positive(o.fibre_piece_mm, "fibre_piece_mm");
    require_positive(o.pla_piece_mm, "pla_piece_mm");
    require_positive(o.time_scale, "time_scale");
    require_positive(o.shortfall_mm, "shortfall_mm");
    require_positive(o.late_cut_mm, "late_cut_mm");
    if (!(o.lead_s >= 0) || !std::isfinite(o.lead_s))
        throw std::invalid_argument("sync: lead_s must be >= 0, got " + std::to_string(o.lead_s));
    if (!(o.min_lead_real_s >= 0) || !std::isfinite(o.min_lead_real_s))
        throw std::invalid_argument("sync: min_lead_real_s must be >= 0, got " +
                                    std::to_string(o.min_lead_real_s));
    if (o.first_event < 1 || o.first_event > events_total + 1)
        throw std::invalid_argument("sync: first_event " + std::to_string(o.first_event) +
                                    " outside 1.." + std::to_string(events_total + 1));
    if (!std::is_sorted(o.skip_events.begin(), o.skip_events.end()) ||
        (!o.skip_events.empty() &&
         (o.skip_events.front() < o.first_event || o.skip_events.back() > events_total)))
        throw std::invalid_argument("sync: skip_events must be sorted events from first_event on");
    if (o.resume_feed) {
        const ResumeFeed& r = *o.resume_feed;
        if (r.rethread && r.sequence != o.first_event)
            throw std::invalid_argument("sync: a rethread resume_feed event " +
                                        std::to_string(r.sequence) + " is not first_event " +
                                        std::to_string(o.first_event));
        if (!r.rethread && (r.sequence < 1 || r.sequence >= o.first_event))
            throw std::invalid_argument("sync: resume_feed event " + std::to_string(r.sequence) +
                                        " is not before first_event " +
                                        std::to_string(o.first_event));
        if (!(r.e_fed_mm >= 0) || !std::isfinite(r.e_fed_mm))
            throw std::invalid_argument("sync: resume_feed e_fed_mm must be >= 0, got " +
                                        std::to_string(r.e_fed_mm));
    }
}

}  // namespace fibrecell::daemon::sync
