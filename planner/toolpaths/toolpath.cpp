#include "planner/toolpaths/toolpath.hpp"

namespace fibrecell::planner {

std::string_view to_string(Head head) {
    return head == Head::pla ? "pla" : "ccf";
}

std::string_view to_string(PathRole role) {
    switch (role) {
        case PathRole::perimeter:
            return "perimeter";
        case PathRole::infill:
            return "infill";
        case PathRole::fibre:
            return "fibre";
        case PathRole::fibre_boundary:
            return "fibre-boundary";
    }
    return "?";
}

}  // namespace fibrecell::planner
