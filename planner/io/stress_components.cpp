#include "planner/io/stress_components.hpp"

namespace fibrecell::planner {

StressTensor stress_from_components(const double* c, int count) {
    StressTensor s;
    if (count == 9) {
        s << c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8];
    } else {
        s << c[0], c[3], c[5],  //
            c[3], c[1], c[4],   //
            c[5], c[4], c[2];
    }
    return s;
}

}  // namespace fibrecell::planner
