#include "planner/fibre/path_chains.hpp"

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

}  // namespace

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
