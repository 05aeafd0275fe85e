#pragma once
// Which triangle of a layer holds a point: a uniform grid of triangle bounding boxes, so a lookup
// only tests the few triangles of one cell.

#include "planner/layers/layer_mesh.hpp"

#include <Eigen/Core>

#include <unordered_map>
#include <vector>

namespace fibrecell::planner {

class TriangleLocator {
  public:
    // cell_mm: grid cell size, about the triangle size. `layer` must outlive the locator.
    TriangleLocator(const LayerMesh& layer, double cell_mm);

    // The triangle containing p (edges included), or -1 outside the layer.
    int locate(const Eigen::Vector2d& p) const;

    // The barycentric interpolation at p of a per-vertex field; `outside` when p is off the layer.
    double interpolate(const std::vector<double>& per_vertex, const Eigen::Vector2d& p,
                       double outside) const;

  private:
    bool contains(int f, const Eigen::Vector2d& p) const;
    long index(double v) const;

    const LayerMesh& layer_;
    double cell_;
    std::unordered_map<long long, std::vector<int>> cells_;
};

}  // namespace fibrecell::planner
