#pragma once
/// @file reduced_order_cells.hpp
/// @brief Small voxel cells and phases for the reduced-order build tests:
/// a z-normal laminate, a cell of a sphere and an ellipsoid in a matrix.

#include "homogenize/grid.hpp"
#include "homogenize/reduced_order_builder.hpp"
#include "materials/law_spec.hpp"
#include "micro/inclusion.hpp"
#include "micro/unit_cell.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lamina::test {

/// A linear elastic phase of stiffness @p C (its law kind @p kind).
inline materials::ReducedOrderPhase elasticPhase(const std::string& name,
                                                 const materials::Stiffness& C, double density,
                                                 materials::LawKind kind) {
  materials::LawSpec law;
  law.kind = kind;
  law.C = C;
  return {name, law, density};
}

/// An isotropic phase.
inline materials::ReducedOrderPhase isotropicPhase(const std::string& name, double E, double nu,
                                                   double density) {
  return elasticPhase(name, materials::Stiffness::isotropic(E, nu), density,
                      materials::LawKind::Isotropic);
}

/// The grid of @p n voxels over a cell of edge @p edge (m) along every axis.
inline homogenize::Grid cubeGrid(std::array<int, 3> n, double edge) {
  homogenize::Grid g;
  g.n = n;
  for (std::size_t d = 0; d < 3; ++d)
    g.h[d] = edge / n[d];
  return g;
}

/// A z-normal laminate: voxel (i, j, k) has phase layer_of[k].
inline std::vector<std::int32_t> laminateMap(std::array<int, 3> n,
                                             const std::vector<std::int32_t>& layer_of) {
  std::vector<std::int32_t> map;
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k)
        map.push_back(layer_of[static_cast<std::size_t>(k)]);
  return map;
}

/// A sphere (phase 1) and an oblique ellipsoid (phase 1) in a matrix (phase
/// 0), a cell of edge 1 mm: no symmetry a laminate or a single sphere has.
inline std::vector<std::int32_t> inclusionsMap(std::array<int, 3> n) {
  micro::Inclusion sphere;
  sphere.shape = micro::Shape::Sphere;
  sphere.phase = 1;
  sphere.semi.setConstant(0.22e-3);
  sphere.center = Eigen::Vector3d(0.3e-3, 0.3e-3, 0.35e-3);
  micro::Inclusion ell;
  ell.shape = micro::Shape::Ellipsoid;
  ell.phase = 1;
  ell.semi = Eigen::Vector3d(0.12e-3, 0.15e-3, 0.3e-3);
  ell.center = Eigen::Vector3d(0.72e-3, 0.7e-3, 0.65e-3);
  ell.R = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  return micro::voxelize({sphere, ell}, n, Eigen::Vector3d::Constant(1e-3));
}

} // namespace lamina::test
