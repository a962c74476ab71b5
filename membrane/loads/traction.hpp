#pragma once
/// @file traction.hpp
/// @brief Consistent nodal forces of a traction on the reference (flat)
/// triangles: the fixed patterns of [[load]] (force over an area, pressure
/// on the linear model, the distributed load of eq. 31).

#include "membrane/model/mesh.hpp"

#include <Eigen/Dense>

#include <vector>

namespace lamina::membrane {

/// Adds to @p f the consistent nodal forces of a traction @p traction(x, y)
/// (N/m^2, a function of the in-plane point) along the unit direction
/// @p dir on the elements @p elems of @p m, on their reference areas,
/// integrated with the 3-point edge-midpoint rule (exact for quadratics).
template <typename F>
void addTraction(const Mesh& m, const std::vector<int>& elems, const Eigen::Vector3d& dir,
                 F&& traction, Eigen::VectorXd& f) {
  for (int e : elems) {
    const auto& t = m.triangles[e];
    const double A = m.area(e);
    for (int q = 0; q < 3; ++q) {
      // Midpoint of edge (q, q+1): N_q = N_{q+1} = 1/2, the third is 0.
      const Eigen::Vector2d p = 0.5 * (m.nodes[t[q]] + m.nodes[t[(q + 1) % 3]]);
      const double w = A / 3 * traction(p);
      for (int k : {q, (q + 1) % 3})
        for (int c = 0; c < 3; ++c)
          f[3 * t[k] + c] += 0.5 * w * dir[c];
    }
  }
}

} // namespace lamina::membrane
