#include "daemon/sync/feed_meter.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace fibrecell::daemon::sync {
namespace {

double round_e(double e_mm) { return std::round(e_mm * 1e5) / 1e5; }

}  // namespace

std::vector<MeterPiece> split_feed(double path_mm, double e_mm, double piece_path_mm) {
    if (!(piece_path_mm > 0)) throw std::invalid_argument("metering: piece length must be positive");
    std::vector<MeterPiece> pieces;
    if (!(path_mm > 0) || !(round_e(e_mm) > 0)) return pieces;
    const auto n = static_cast<std::size_t>(std::ceil(path_mm / piece_path_mm - 1e-9));
    double e_before = 0;
    for (std::size_t i = 1; i <= n; ++i) {
        const double e_after = round_e(e_mm * static_cast<double>(i) / static_cast<double>(n));
        if (e_after > e_before)
            pieces.push_back({path_mm * static_cast<double>(i) / static_cast<double>(n),
                              round_e(e_after - e_before)});
        e_before = e_after;
    }
    return pieces;
}

FeedMeter::FeedMeter(std::vector<MeterPiece> pieces, MeterPacing pacing,
                     SteadyClock::time_point robot_start)
    : pieces_(std::move(pieces)), pacing_(pacing), robot_start_(robot_start) {}

SteadyClock::time_point FeedMeter::due(std::size_t i) const {
    // Robot time (simulated seconds) at which it is lead_s of path short of the piece's end.
    const double robot_s = pieces_[i].path_end_mm / pacing_.speed_mm_s - pacing_.lead_s;
    return robot_start_ + std::chrono::duration_cast<SteadyClock::duration>(
                              std::chrono::duration<double>(robot_s / pacing_.time_scale));
}

void FeedMeter::skip_fed(double e_mm, SteadyClock::time_point now) {
    if (!(e_mm >= 0) || e_mm > e_total_mm() + 1e-6)
        throw std::invalid_argument("metering: " + std::to_string(e_mm) + " mm fed is outside 0.." +
                                    std::to_string(e_total_mm()) + " mm of the path's feed");
    double fed = 0;
    std::size_t k = 0;
    while (k < pieces_.size() && fed + pieces_[k].e_mm <= e_mm + 1e-6) fed += pieces_[k++].e_mm;
    double at_mm = k == 0 ? 0 : pieces_[k - 1].path_end_mm;
    if (const double part = round_e(e_mm - fed); k < pieces_.size() && part > 0) {
        // It ends inside piece k (a reset lost the end of what the board had taken): the rest
        // of that piece is fed first, and the robot stands where the fed part ends.
        MeterPiece& rest = pieces_[k];
        const double share = part / rest.e_mm;
        at_mm += share * (rest.path_end_mm - at_mm);
        if (round_e(rest.e_mm - part) > 0) {
            rest.e_mm = round_e(rest.e_mm - part);
            fed_inside_piece_mm_ = part;
        } else {
            ++k;  // fed but for less than the G-code's resolution
        }
    }
    next_ = k;
    robot_start_ = now - std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(
                             at_mm / pacing_.speed_mm_s / pacing_.time_scale));
}

std::vector<MeterPiece> FeedMeter::take_due(SteadyClock::time_point now) {
    std::vector<MeterPiece> out;
    while (!paused() && next_ < pieces_.size() && due(next_) <= now) out.push_back(pieces_[next_++]);
    return out;
}

std::optional<SteadyClock::time_point> FeedMeter::next_due() const {
    if (paused() || next_ >= pieces_.size()) return std::nullopt;
    return due(next_);
}

void FeedMeter::pause(SteadyClock::time_point now) {
    if (!paused_at_) paused_at_ = now;
}

void FeedMeter::resume(SteadyClock::time_point now) {
    if (!paused_at_) return;
    robot_start_ += now - *paused_at_;
    paused_at_.reset();
}

double FeedMeter::e_sent_mm() const {
    const auto end = pieces_.begin() + static_cast<std::ptrdiff_t>(next_);
    return std::accumulate(pieces_.begin(), end, fed_inside_piece_mm_,
                           [](double s, const MeterPiece& p) { return s + p.e_mm; });
}

double FeedMeter::e_total_mm() const {
    return std::accumulate(pieces_.begin(), pieces_.end(), fed_inside_piece_mm_,
                           [](double s, const MeterPiece& p) { return s + p.e_mm; });
}

}  // namespace fibrecell::daemon::sync
