#include "planner/fibre/spacing_trim.hpp"

#include "planner/fibre/laid_fibre.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fibrecell::planner {
namespace {

// i with its lowest `bits` bits reversed: the coarse-to-fine rank of level i.
unsigned reversed(unsigned i, int bits) {
    unsigned r = 0;
    for (int b = 0; b < bits; ++b) r |= ((i >> b) & 1u) << (bits - 1 - b);
    return r;
}

}  // namespace

std::vector<Polyline> trim_to_spacing(const std::vector<Polyline>& curves, int n,
                                      const SpacingTrimOptions& options) {
    int bits = 0;
    while ((1 << bits) < std::max(n, 1)) ++bits;
    std::vector<std::size_t> order(curves.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return reversed(static_cast<unsigned>(curves[a].level), bits) <
               reversed(static_cast<unsigned>(curves[b].level), bits);
    });

    LaidFibre laid(options.spacing_mm);
    std::vector<Polyline> out;
    for (std::size_t index : order)
        for (LaidPiece& piece :
             laid.lay(curves[index].points, curves[index].closed, options.min_piece_mm))
            out.push_back({std::move(piece.points), piece.closed, curves[index].level});
    return out;
}

}  // namespace fibrecell::planner
