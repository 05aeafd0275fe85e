#pragma once
// The paper's Section 5.1 analyses as small SVG charts for preview/: the histogram of neighbour
// dot products after re-orientation (Fig. 8) and a parameter sweep's fibre length (Fig. 9).
// Self-contained documents, no scripts or external resources.

#include "planner/field/incompatibility.hpp"
#include "planner/plan/parameter_sweep.hpp"

#include <string>

namespace fibrecell::planner {

// Bars of the pairs' share per bin, with the threshold eta drawn as a line. One
// <rect class="bar"> per bin, in bin order.
std::string neighbour_dots_svg(const DotHistogram& dots, double eta);

// Fibre length [m] against the swept value, one <circle class="point"> per point in sweep order.
std::string sweep_svg(const ParameterSweep& sweep);

}  // namespace fibrecell::planner
