#pragma once
// The fibre of one layer laid so far, and what of the next path may still go down: W from every
// ribbon already laid and from itself wherever it comes back (a hairpin, a zigzag stub, a ring
// closing on its own start). Paths laid one after the other are cut where they would crowd; what
// is kept is measured against everything, so no two kept points are nearer than W.

#include "planner/fibre/segment_grid.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

struct LaidPiece {
    std::vector<Eigen::Vector2d> points;  // [mm]: the path's own vertices, and the cut ends
    bool closed = false;
};

class LaidFibre {
  public:
    // w: the spacing W [mm] to keep, less tolerance_mm: Clipper's round joins lie up to 2.25
    // arc tolerances (0.0045 mm at the default 0.002) inside their arcs, so rings offset exactly
    // W from each other must still fit.
    explicit LaidFibre(double w, double tolerance_mm = 0.005);

    // Lays `points` (closed: a loop) after what is already laid and returns the pieces kept, in
    // path order. Resampled every W/4 (for the check only), a point is kept when it lies at least W
    // from every laid segment: those of earlier paths, of earlier pieces of this one, and of this
    // piece more than 4W behind it along the path (measured from segments 3.75W back, so that a
    // point between two samples is covered too). (Between two kept points W/4 apart, a laid
    // corner can come up to 0.8% nearer than W.) A loop that needs no cut stays closed. Pieces
    // shorter than min_piece_mm are neither returned nor laid.
    std::vector<LaidPiece> lay(const std::vector<Eigen::Vector2d>& points, bool closed,
                               double min_piece_mm = 0);

    // Pieces left out so far for being shorter than min_piece_mm.
    int dropped_short() const { return dropped_short_; }
    double dropped_short_mm() const { return dropped_short_mm_; }  // their length

  private:
    // `pts` resampled, `vertex` flags the path's own vertices among them.
    std::vector<LaidPiece> lay_open(const std::vector<Eigen::Vector2d>& pts,
                                    const std::vector<char>& vertex, double min_piece_mm);
    bool near(const SegmentGrid& grid, const Eigen::Vector2d& p) const;
    bool keeps_itself(const std::vector<Eigen::Vector2d>& loop) const;
    void commit(const LaidPiece& piece);

    double w_;
    double keep_;  // W less the tolerance
    SegmentGrid grid_;
    int dropped_short_ = 0;
    double dropped_short_mm_ = 0;
};

}  // namespace fibrecell::planner
