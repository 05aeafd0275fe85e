#pragma once
// Host metering of one path's feed (docs/sync-engine.md, "Why this design"): instead of one
// long G1 E move the feed goes to the board in small pieces, each released when the robot is
// expected to be at most `lead_s` of path behind the piece's end. The board then never holds
// more than about the lead, so a pause stops the feed within the lead, and a stopped meter drops
// only unsent pieces. Pure timing: the caller turns pieces into G-code and sends them.

#include <chrono>
#include <cstddef>
#include <optional>
#include <vector>

namespace fibrecell::daemon::sync {

using SteadyClock = std::chrono::steady_clock;

struct MeterPiece {
    double path_end_mm = 0;  // where along the path the piece ends
    double e_mm = 0;         // feed of this piece (E, relative)
};

// `e_mm` of feed over `path_mm` of path in equal pieces of at most `piece_path_mm` of path. Each
// piece's E is a difference of cumulative amounts rounded to 1e-5 mm (the G-code resolution), so
// the pieces add up to exactly round(e_mm, 1e-5); pieces that round to nothing are left out.
// Empty when there is nothing to feed. Throws std::invalid_argument for piece_path_mm <= 0.
std::vector<MeterPiece> split_feed(double path_mm, double e_mm, double piece_path_mm);

struct MeterPacing {
    double speed_mm_s = 1;  // programmed TCP speed along the path
    double lead_s = 0.3;    // feed sent ahead of the robot [s of path]
    double time_scale = 1;  // simulated seconds per real second (1 on the real cell)
};

class FeedMeter {
  public:
    // The robot is taken to be at the path start at `robot_start` and to move at the pacing speed
    // (real time scaled by time_scale) except while paused.
    FeedMeter(std::vector<MeterPiece> pieces, MeterPacing pacing, SteadyClock::time_point robot_start);

    // Resuming a path: the feed up to `e_mm` (what the board already fed) counts as sent, a
    // piece it ends inside keeps only its rest, and the robot is taken to be where that feed
    // ends at `now`. Throws std::invalid_argument when `e_mm` is outside 0..e_total_mm().
    void skip_fed(double e_mm, SteadyClock::time_point now);

    // The pieces due at `now`, in order; each is handed out once.
    std::vector<MeterPiece> take_due(SteadyClock::time_point now);
    // When the next piece falls due; empty when all were handed out or while paused.
    std::optional<SteadyClock::time_point> next_due() const;

    // A pause freezes the robot's expected position; resume() continues from it.
    void pause(SteadyClock::time_point now);
    void resume(SteadyClock::time_point now);
    bool paused() const { return paused_at_.has_value(); }

    std::size_t sent() const { return next_; }
    std::size_t total() const { return pieces_.size(); }
    double e_sent_mm() const;
    double e_total_mm() const;
    double e_left_mm() const { return e_total_mm() - e_sent_mm(); }

  private:
    SteadyClock::time_point due(std::size_t i) const;

    std::vector<MeterPiece> pieces_;
    MeterPacing pacing_;
    SteadyClock::time_point robot_start_;  // moved on by every pause's length
    std::optional<SteadyClock::time_point> paused_at_;
    std::size_t next_ = 0;
    double fed_inside_piece_mm_ = 0;  // skip_fed's share of the piece it ended inside
};

}  // namespace fibrecell::daemon::sync
