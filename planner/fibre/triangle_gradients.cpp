#include "planner/fibre/triangle_gradients.hpp"

#include <stdexcept>
#include <string>

namespace fibrecell::planner {
namespace {

// Left normal of an edge: for a counter-clockwise triangle it points into the triangle.
Eigen::Vector2d left_normal(const Eigen::Vector2d& d) {
    return {-d.y(), d.x()};
}

}  // namespace

TriangleGradients triangle_gradients(const LayerMesh& layer, int f) {
    const auto& t = layer.triangles[f];
    const Eigen::Vector2d& p0 = layer.vertices[t[0]];
    const Eigen::Vector2d& p1 = layer.vertices[t[1]];
    const Eigen::Vector2d& p2 = layer.vertices[t[2]];
    const Eigen::Vector2d e1 = p1 - p0, e2 = p2 - p0;
    const double twice_area = e1.x() * e2.y() - e1.y() * e2.x();
    if (!(twice_area > 0))
        throw std::invalid_argument("layer at z = " + std::to_string(layer.z) + ": triangle " +
                                    std::to_string(f) + " has no positive area");
    return {0.5 * twice_area,
            {left_normal(p2 - p1) / twice_area, left_normal(p0 - p2) / twice_area,
             left_normal(p1 - p0) / twice_area}};
}

}  // namespace fibrecell::planner
