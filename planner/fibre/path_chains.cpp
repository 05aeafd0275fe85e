#include "planner/fibre/path_chains.hpp"

#include "planner/fibre/curve_spacing.hpp"

#include <algorithm>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

// For every piece end, the link that leaves it (or -1).
struct EndLinks {
    std::vector<int> at[2];  // [0]: first point, [1]: last point

    explicit EndLinks(std::size_t pieces)
        : at{std::vector<int>(pieces, -1), std::vector<int>(pieces, -1)} {}
    int& operator()(const PieceEnd& e) { return at[e.last][e.piece]; }
};

bool same_end(const PieceEnd& a, const PieceEnd& b) {
    return a.piece == b.piece && a.last == b.last;
}

// The fibre as it leaves the piece end `e` inwards, through the links already made, until it
// has run `reach` mm or ends: its points in order from e.
std::vector<Eigen::Vector2d> fibre_from(const std::vector<Polyline>& pieces,
                                        const std::vector<Link>& links, PieceEnd e, double reach) {
    std::vector<Eigen::Vector2d> out;
    double along = 0;
    auto add = [&](const Eigen::Vector2d& p) {
        if (!out.empty()) along += (p - out.back()).norm();
        out.push_back(p);
    };
    const int start = e.piece;
    for (std::size_t hops = 0; hops <= links.size(); ++hops) {
        const auto& pts = pieces[e.piece].points;
        for (std::size_t k = 0; k < pts.size() && along <= reach; ++k)
            add(pts[e.last ? pts.size() - 1 - k : k]);
        if (along > reach) break;
        const PieceEnd other{e.piece, !e.last};
        const auto l = std::find_if(links.begin(), links.end(), [&](const Link& x) {
            return same_end(x.from, other) || same_end(x.to, other);
        });
        if (l == links.end()) break;
        const bool forward = same_end(l->from, other);
        if (forward)
            for (const auto& p : l->between) add(p);
        else
            for (auto it = l->between.rbegin(); it != l->between.rend(); ++it) add(*it);
        e = forward ? l->to : l->from;
        if (e.piece == start) break;
    }
    return out;
}

}  // namespace

bool join_keeps_spacing(const std::vector<Polyline>& pieces, const std::vector<Link>& made,
                        const Link& link, double w, double reach_mm) {
    const double reach = reach_mm > 0 ? reach_mm : 8 * w;
    if (link.from.piece == link.to.piece) {  // the piece closes on itself: check the whole loop
        std::vector<Eigen::Vector2d> loop = pieces[link.from.piece].points;
        // `between` runs from the `from` end: after the last point when that is where it leaves.
        if (link.from.last)
            loop.insert(loop.end(), link.between.begin(), link.between.end());
        else
            loop.insert(loop.end(), link.between.rbegin(), link.between.rend());
        return min_fibre_spacing({loop}, {1}, 4 * w, w) >= w * (1 - 1e-9);
    }
    // The fibre as it runs through the join: into `from`'s end, along the link, out of `to`.
    std::vector<Eigen::Vector2d> fibre = fibre_from(pieces, made, link.from, reach);
    std::reverse(fibre.begin(), fibre.end());
    fibre.insert(fibre.end(), link.between.begin(), link.between.end());
    const std::vector<Eigen::Vector2d> out = fibre_from(pieces, made, link.to, reach);
    fibre.insert(fibre.end(), out.begin(), out.end());
    return min_fibre_spacing({fibre}, {0}, 4 * w, w) >= w * (1 - 1e-9);
}

ChainSets::ChainSets(std::size_t pieces) : parent_(pieces) {
    for (std::size_t i = 0; i < pieces; ++i) parent_[i] = static_cast<int>(i);
}

int ChainSets::find(int piece) {
    while (parent_[piece] != piece) piece = parent_[piece] = parent_[parent_[piece]];
    return piece;
}

bool ChainSets::try_join(const PieceEnd& a, const PieceEnd& b) {
    if (a.piece == b.piece) return true;
    const int ra = find(a.piece), rb = find(b.piece);
    if (ra == rb) return false;
    parent_[ra] = rb;
    return true;
}

const Eigen::Vector2d& end_point(const std::vector<Polyline>& pieces, const PieceEnd& end) {
    const auto& pts = pieces[end.piece].points;
    return end.last ? pts.back() : pts.front();
}

std::vector<Polyline> join_pieces(const std::vector<Polyline>& pieces,
                                  const std::vector<Link>& links) {
    EndLinks link_at(pieces.size());
    for (std::size_t l = 0; l < links.size(); ++l)
        for (const PieceEnd& e : {links[l].from, links[l].to}) {
            if (pieces[e.piece].closed)
                throw std::invalid_argument("join_pieces: a closed curve cannot be linked");
            if (link_at(e) >= 0)
                throw std::invalid_argument("join_pieces: a piece end is linked twice");
            link_at(e) = static_cast<int>(l);
        }

    std::vector<char> used(pieces.size(), 0);
    std::vector<Polyline> out;
    // Walks a chain from `entry` (the end it is entered at) until it runs out or comes back.
    auto walk = [&](PieceEnd entry) {
        Polyline chain;
        chain.level = pieces[entry.piece].level;
        const PieceEnd start = entry;
        while (true) {
            used[entry.piece] = 1;
            const auto& pts = pieces[entry.piece].points;
            if (entry.last)
                chain.points.insert(chain.points.end(), pts.rbegin(), pts.rend());
            else
                chain.points.insert(chain.points.end(), pts.begin(), pts.end());
            const PieceEnd exit{entry.piece, !entry.last};
            const int l = link_at(exit);
            if (l < 0) break;
            const Link& link = links[l];
            const bool forward = link.from.piece == exit.piece && link.from.last == exit.last;
            const PieceEnd next = forward ? link.to : link.from;
            if (forward)
                chain.points.insert(chain.points.end(), link.between.begin(), link.between.end());
            else
                chain.points.insert(chain.points.end(), link.between.rbegin(), link.between.rend());
            if (next.piece == start.piece && next.last == start.last) {
                chain.closed = true;
                break;
            }
            entry = next;
        }
        out.push_back(std::move(chain));
    };

    for (std::size_t i = 0; i < pieces.size(); ++i) {
        if (pieces[i].closed) {
            used[i] = 1;
            out.push_back(pieces[i]);
            continue;
        }
        const int p = static_cast<int>(i);
        if (used[i]) continue;
        // Start chains at a free end, so an open chain comes out whole.
        if (link_at(PieceEnd{p, false}) < 0)
            walk({p, false});
        else if (link_at(PieceEnd{p, true}) < 0)
            walk({p, true});
    }
    // What is left is linked at both ends all round: cycles.
    for (std::size_t i = 0; i < pieces.size(); ++i)
        if (!used[i]) walk({static_cast<int>(i), false});
    return out;
}

}  // namespace fibrecell::planner
