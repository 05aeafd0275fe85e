// planner.fibre_budget: the search on a known length curve, then the tensile bar planned to a
// length per layer by both strategies, measured from the paths themselves.

#include "planner/plan/fibre_budget.hpp"

#include "planner/job/job_spec.hpp"
#include "planner/plan/layer_stage.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fibrecell::planner;

namespace {

// Fibre of every CCF layer [mm], summed from the path points.
std::vector<double> ccf_lengths(const LayerStageResult& r) {
    std::vector<double> out;
    for (const ToolpathLayer& layer : r.layers) {
        if (layer.head != Head::ccf) continue;
        double mm = 0;
        for (const Toolpath& p : layer.paths) {
            for (std::size_t k = 1; k < p.points.size(); ++k)
                mm += (p.points[k] - p.points[k - 1]).norm();
            if (p.closed) mm += (p.points.front() - p.points.back()).norm();
        }
        out.push_back(mm);
    }
    return out;
}

JobSpec tensile_bar(const std::string& budget, Strategy strategy) {
    JobSpec job = load_job_file(fibrecell::test::source_path("examples/tensile-bar/tensile-bar.job.yaml"));
    job.planner.strategy = strategy;
    if (budget == "baseline")
        job.planner.fibre_budget.kind = FibreBudget::Kind::baseline;
    else
        job.planner.fibre_budget = {FibreBudget::Kind::metres_per_layer, std::stod(budget)};
    return job;
}

}  // namespace

TEST(FitBudget, FindsTheKnobOfARisingLengthWithinFivePercent) {
    int plans = 0;
    const auto plan = [&](double knob) {
        ++plans;
        return 1000 * std::floor(10 * std::sqrt(knob)) / 10;  // steps of 100 mm
    };
    const auto length = [](double mm) { return mm; };
    BudgetFit fit;
    const double laid = fit_budget(plan, length, 2000, 1.0 / 16, 16, 1, fit);
    EXPECT_TRUE(fit.met());
    EXPECT_NEAR(laid, 2000, 100);
    EXPECT_EQ(fit.tries, plans);
    EXPECT_LE(plans, 10);
}

// The baseline's fibre: rings round the outline, then zigzag in proportion to its density. Aimed
// along the line, one step meets what halving the bracket takes several for; on the step curve
// above it still meets within the tries.
TEST(FitBudget, AProportionalKnobIsMetInOneStepAfterTheBracket) {
    const auto plans_for = [](KnobShape shape) {
        int plans = 0;
        const auto plan = [&](double knob) {
            ++plans;
            return 1800 + 6400 * knob;
        };
        BudgetFit fit;
        fit_budget(plan, [](double mm) { return mm; }, 4464, 1.0 / 32, 1, 1, fit, shape);
        EXPECT_TRUE(fit.met());
        return plans;
    };
    EXPECT_EQ(plans_for(KnobShape::proportional), 3);  // the start, the far end, one step
    EXPECT_GT(plans_for(KnobShape::uneven), 3);
    int plans = 0;
    const auto steps = [&](double knob) {
        ++plans;
        return 1000 * std::floor(10 * std::sqrt(knob)) / 10;
    };
    BudgetFit fit;
    fit_budget(steps, [](double mm) { return mm; }, 2000, 1.0 / 16, 16, 1, fit, KnobShape::proportional);
    EXPECT_TRUE(fit.met());
    EXPECT_LE(plans, 10);
}

TEST(FitBudget, AnUnreachableTargetStopsAtTheFullEndAndSaysSo) {
    const auto plan = [](double knob) { return std::min(knob, 4.0) * 100; };
    const auto length = [](double mm) { return mm; };
    BudgetFit fit;
    EXPECT_DOUBLE_EQ(fit_budget(plan, length, 1000, 1.0 / 16, 16, 1, fit), 400);
    EXPECT_FALSE(fit.met());
    EXPECT_EQ(fit.tries, 2);  // the start and the far end
    EXPECT_DOUBLE_EQ(fit.knob, 16);
}

// Every strategy meets a length per CCF layer that lies between what it lays by itself (field
// 1.52 m, contour-zigzag 2.29 m, field-dense 1.79 m per layer) and nothing: field-dense by
// thinning its stripes, with no gap fill after them.
TEST(FibreBudget, EveryStrategyLaysTheMetresPerLayerAskedWithinFivePercent) {
    for (const auto& [strategy, metres] :
         {std::pair{Strategy::field, 1.2}, std::pair{Strategy::contour_zigzag, 1.5},
          std::pair{Strategy::field_dense, 1.2}}) {
        SCOPED_TRACE(std::string(to_string(strategy)));
        const JobSpec job = tensile_bar(std::to_string(metres), strategy);
        const LayerStageResult r = run_layer_stage(job, fibrecell::test::field_stage_of(job));
        const std::vector<double> lengths = ccf_lengths(r);
        ASSERT_EQ(lengths.size(), 5u);
        for (double mm : lengths) EXPECT_NEAR(mm, metres * 1000, 0.05 * metres * 1000);
        EXPECT_EQ(r.stats.budget.layers, 5);
        EXPECT_EQ(r.stats.budget.layers_met, 5);
        EXPECT_LE(r.stats.budget.worst_error, 0.05);
        EXPECT_TRUE(r.warnings.empty());
    }
}

// More than the job's own p lays (1.52 m per layer) is met by lowering the contrast, as the paper
// tuned its parameters to compare at the same fibre: the fibre still runs the bar's length and
// stays densest in the gauge, where more isocurves cut back to W would not.
TEST(FibreBudget, MoreThanTheJobLaysIsMetByLoweringTheContrastFirst) {
    const JobSpec job = tensile_bar("1.7", Strategy::field);
    const LayerStageResult r = run_layer_stage(job, fibrecell::test::field_stage_of(job));
    for (double mm : ccf_lengths(r)) EXPECT_NEAR(mm, 1700, 0.05 * 1700);
    EXPECT_EQ(r.stats.budget.layers_met, 5);
    EXPECT_EQ(r.stats.budget.p_layers, 5);
    EXPECT_GT(r.stats.budget.lowest_p, 0.0);
    EXPECT_LT(r.stats.budget.highest_p, job.planner.p);
    // 0.85 measured (0.90 at the job's own 1.52 m); more isocurves at p = 1 give 0.39.
    EXPECT_GT(r.stats.quality.density_correlation(), 0.8);
    EXPECT_GT(r.stats.fibre_min_length_mm, 60.0);
}

// The baseline's 2.29 m per layer is more than the field strategy can lay W apart on the bar:
// it lays as much as it can, more than by itself, and each layer says the budget was not met.
TEST(FibreBudget, ABaselineBudgetTheLayerCannotHoldIsApproachedAndReported) {
    const JobSpec job = tensile_bar("baseline", Strategy::field);
    const FieldStageResult field = fibrecell::test::field_stage_of(job);
    const LayerStageResult r = run_layer_stage(job, field);
    JobSpec plain = job;
    plain.planner.fibre_budget = {};
    const LayerStageResult own = run_layer_stage(plain, field);
    EXPECT_GT(r.stats.fibre_length_mm, 1.05 * own.stats.fibre_length_mm);
    EXPECT_EQ(r.stats.budget.layers, 5);
    EXPECT_EQ(r.stats.budget.layers_met, 0);
    EXPECT_NEAR(r.stats.budget.target_mm / 1000, 11.47, 0.1);
    ASSERT_EQ(r.warnings.size(), 5u);
    EXPECT_NE(r.warnings[0].find("fibre budget"), std::string::npos);
    EXPECT_NE(r.warnings[0].find("holds no more fibre W apart"), std::string::npos);
    EXPECT_GE(r.stats.fibre_min_spacing_mm, 0.99);
}
