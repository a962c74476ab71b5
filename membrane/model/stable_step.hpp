#pragma once
/// @file stable_step.hpp
/// @brief Critical step of explicit central differences on linear triangles
/// with a lumped mass: dt_e = L_e / c_e, L_e = 2 A_e / (longest edge) (the
/// smallest altitude, LS-DYNA's length for triangular shells), c_e the
/// fastest plane-wave speed of the element's stiffness over all in-plane
/// directions n: c^2 = max_n lambda_max(B(n)^T D B(n)) / rho (the acoustic
/// tensor), plus the pre-tension's T / (rho h) for the large-deflection model.

#include "membrane/model/mesh.hpp"

#include <Eigen/Dense>

#include <vector>

namespace lamina::membrane {

/// Which strain a stiffness acts on.
enum class StrainKind {
  Lamina6,    ///< the paper's 6 strains [u_x, v_y, 0, u_y + v_x, w_y, w_x] on (u, v, w)
  PlaneStress ///< [E11, E22, 2 E12] on the in-plane (u1, u2)
};

/// @return the largest eigenvalue of the acoustic tensor of @p D over in-plane
/// directions (Pa; 1 degree steps, the maximum of a smooth function of the angle).
double maxWaveModulus(const Eigen::MatrixXd& D, StrainKind kind);

/// @return the characteristic length 2 A / (longest edge) of triangle @p e (3D, m)
double elementLength(const Mesh& mesh, int e);

/// @return min over elements of elementLength / speed[region of e] (s)
double criticalStep(const Mesh& mesh, const std::vector<double>& speed);

} // namespace lamina::membrane
