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

// How the fibre rises with the knob, which decides where the search looks next.
enum class KnobShape {
    proportional,  // about in proportion (the baseline's zigzag density): aim along the line
    uneven,        // steps and plateaus (the field strategies): halve the bracket
};

// plan(knob) makes the layer at a density knob in [lo, hi] (the fibre rises with it, not
// necessarily steadily); length(result) is its fibre [mm]. Starts at `start`, brackets the target
// and closes in on it for at most `max_tries` plans; returns the plan nearest the target and fills
// `fit`. A proportional knob steps to where the line through the bracket's two plans meets the
// target (false position, Illinois variant: one step usually meets it on the baseline, where
// halving took five or six); an uneven one bisects the bracket geometrically (false position
// there aimed at dense, slow plans and took as many steps).
template <class Plan, class Length>
auto fit_budget(Plan&& plan, Length&& length, double target_mm, double lo, double hi, double start,
                BudgetFit& fit, KnobShape shape = KnobShape::uneven, int max_tries = 10) {
    fit = {.target_mm = target_mm};
    auto best = plan(start);
    fit.laid_mm = length(best);
    fit.knob = start;
    fit.tries = 1;
    // Plans at `knob`; keeps it when nearer the target. Returns its fibre [mm].
    const auto attempt = [&](double knob) {
        auto candidate = plan(knob);
        const double mm = length(candidate);
        ++fit.tries;
        if (std::abs(mm - target_mm) < std::abs(fit.laid_mm - target_mm)) {
            best = std::move(candidate);
            fit.laid_mm = mm;
            fit.knob = knob;
        }
        return mm;
    };
    if (fit.met()) return best;
    const double start_mm = fit.laid_mm;
    // The far end in the direction needed first: if even that misses, nothing between can do
    // better (the layer holds no more, or cannot be made sparser).
    const bool more = fit.laid_mm < target_mm;
    const double far = more ? hi : lo;
    const double far_mm = attempt(far);
    if ((far_mm < target_mm) == more) return best;
    // The bracket: a knob that gave too little and one that gave enough, with their misses [mm]
    // (the Illinois step halves a kept end's miss, so that a curved length cannot pin it).
    double little = more ? start : far, enough = more ? far : start;
    double little_miss = (more ? start_mm : far_mm) - target_mm;
    double enough_miss = (more ? far_mm : start_mm) - target_mm;
    int kept = 0;  // which end stayed last time: -1 little, +1 enough
    while (!fit.met() && fit.tries < max_tries) {
        const double span = enough - little;
        double knob = little - little_miss * span / (enough_miss - little_miss);
        // Not within a twentieth of the bracket's ends (or no line at all): its geometric middle.
        if (shape == KnobShape::uneven || !std::isfinite(knob) ||
            !(std::abs(knob - little) > 0.05 * std::abs(span) &&
              std::abs(enough - knob) > 0.05 * std::abs(span)))
            knob = std::sqrt(little * enough);
        const double miss = attempt(knob) - target_mm;
        if (miss < 0) {
            little = knob, little_miss = miss;
            if (kept == 1) enough_miss /= 2;
            kept = 1;
        } else {
            enough = knob, enough_miss = miss;
            if (kept == -1) little_miss /= 2;
            kept = -1;
        }
    }
    return best;
}

}  // namespace fibrecell::planner
