#pragma once
// Meeting a fibre budget on one CCF layer (planner.fibre_budget): a strategy's density knob (the
// field strategy's contrast p and isocurve count, the baseline's zigzag density) is searched until
// the layer's fibre is within 5% of the target, or as near as the layer allows (a layer holds only
// so much fibre W apart; a sparse one needs none at all).

#include <cmath>
#include <utility>

namespace fibrecell::planner {

struct BudgetFit {
    double target_mm = 0;  // what the layer should get
    double laid_mm = 0;    // what it got
    double knob = 1;       // the density the plan was made at
    int tries = 0;         // plans made
    bool met() const { return std::abs(laid_mm - target_mm) <= tolerance * target_mm; }
    static constexpr double tolerance = 0.05;
};

// plan(knob) makes the layer at a density knob in [lo, hi] (the fibre rises with it, not
// necessarily steadily); length(result) is its fibre [mm]. Starts at `start`, brackets the target
// and bisects (geometrically) for at most `max_tries` plans; returns the plan nearest the target
// and fills `fit`.
template <class Plan, class Length>
auto fit_budget(Plan&& plan, Length&& length, double target_mm, double lo, double hi, double start,
                BudgetFit& fit, int max_tries = 10) {
    fit = {.target_mm = target_mm};
    auto best = plan(start);
    fit.laid_mm = length(best);
    fit.knob = start;
    fit.tries = 1;
    // Plans at `knob`; keeps it when nearer the target. Returns whether it gave too little.
    const auto attempt = [&](double knob) {
        auto candidate = plan(knob);
        const double mm = length(candidate);
        ++fit.tries;
        if (std::abs(mm - target_mm) < std::abs(fit.laid_mm - target_mm)) {
            best = std::move(candidate);
            fit.laid_mm = mm;
            fit.knob = knob;
        }
        return mm < target_mm;
    };
    if (fit.met()) return best;
    // The far end in the direction needed first: if even that misses, nothing between can do
    // better (the layer holds no more, or cannot be made sparser).
    const bool more = fit.laid_mm < target_mm;
    if (attempt(more ? hi : lo) == more) return best;
    double too_little = more ? start : lo, too_much = more ? hi : start;
    while (!fit.met() && fit.tries < max_tries) {
        const double knob = std::sqrt(too_little * too_much);
        (attempt(knob) ? too_little : too_much) = knob;
    }
    return best;
}

}  // namespace fibrecell::planner
