#include "planner/plan/fea_load_case.hpp"

#include "planner/mesh/region.hpp"

#include <stdexcept>

namespace fibrecell::planner {

LoadCase fea_load_case(const JobSpec& job, const LoadCaseSpec& spec, const VolumeModel& model,
                       const std::vector<BoundaryTriangle>& boundary) {
    LoadCase lc;
    lc.material = {spec.youngs_modulus_mpa, spec.poisson_ratio};
    auto triangles_of = [&](const std::string& name, const char* use) {
        const Region* region = job.find_region(name);
        auto tris = select_triangles(model, boundary, *region);
        if (tris.empty())
            throw std::invalid_argument("region '" + name + "' (" + use +
                                        ") selects no boundary triangle of the mesh");
        return tris;
    };
    for (const auto& name : spec.supports)
        lc.supports.push_back({name, triangle_vertices(triangles_of(name, "support"))});
    for (const auto& load : spec.loads)
        lc.loads.push_back({load.region, triangles_of(load.region, "load"), load.force_n});
    return lc;
}

}  // namespace fibrecell::planner
