#pragma once
// Joining fibre curves end to end (paper Section 4.4, Steps 3-4): pieces are open polylines,
// links say which end meets which and along what, and the chains they form become single
// continuous fibre paths.

#include "planner/fibre/isocurves.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

struct PieceEnd {
    int piece = 0;
    bool last = false;  // false: the piece's first point; true: its last point
};

struct Link {
    PieceEnd from, to;
    std::vector<Eigen::Vector2d> between;  // points strictly between the two ends, from -> to
};

// Which pieces links have already tied into one chain (union-find), so that a new link can be
// refused when it would close a chain of several pieces into a loop: a serpentine prints in one
// go, a ring of two runs leaves its neighbours unjoined.
class ChainSets {
  public:
    explicit ChainSets(std::size_t pieces);
    int find(int piece);
    // Records the link; false (and nothing recorded) when it would close a loop of two or more
    // pieces. A piece's ends joined to each other (it closes on itself) are accepted.
    bool try_join(const PieceEnd& a, const PieceEnd& b);

  private:
    std::vector<int> parent_;
};

// The end point of a piece [mm].
const Eigen::Vector2d& end_point(const std::vector<Polyline>& pieces, const PieceEnd& end);

// Whether the fibre joined along `link` keeps W from itself near the join: no two points closer
// than w that lie more than 4w apart along the joined fibre, over the link and `reach_mm` (8W
// when 0) of fibre on either side, followed through the links already `made`. A link that folds
// back on a piece (a V-shaped cusp, a hairpin tighter than W) fails.
bool join_keeps_spacing(const std::vector<Polyline>& pieces, const std::vector<Link>& made,
                        const Link& link, double w, double reach_mm = 0);

// Joins `pieces` along `links` (each piece end used by at most one link; closed pieces are
// passed through untouched and must not be linked). Every chain becomes one polyline, closed when
// its links form a cycle. Throws std::invalid_argument when an end is linked twice.
std::vector<Polyline> join_pieces(const std::vector<Polyline>& pieces,
                                  const std::vector<Link>& links);

}  // namespace fibrecell::planner
