#pragma once
/// @file kinematics.hpp
/// @brief Finite-deformation steps seen in the rotation-free frame of the
/// Green-Naghdi rate (polyurea chapter eq. 5), and small-strain conversions.
///
/// With F = R U (polar decomposition), the Green-Naghdi rate of a tensor is
/// R d/dt (R^T sigma R) R^T, so a rate law written with it is an ordinary
/// rate law for sigma_hat = R^T sigma R driven by D_hat = R^T D R. One step
/// F_n -> F is taken at the midpoint (Hughes-Winget): with F_m = (F_n + F)/2,
///     D dt = sym((F - F_n) F_m^-1),    d eps_hat = R_m^T (D dt) R_m,
/// and sigma = R sigma_hat R^T at t_{n+1}. For a rigid rotation (F_n, F
/// orthogonal) (F - F_n) F_m^-1 is the Cayley transform of F F_n^T, which is
/// skew: the strain increment is exactly zero and the stress invariants are
/// unchanged.

#include "materials/law.hpp"

#include <Eigen/Dense>

namespace lamina::materials {

/// @return the rotation R of F = R U (det F > 0), by Newton's iteration
/// for the polar factor (the SVD when it does not converge)
Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& F);

/// One step F_n -> F in the rotation-free frame.
struct FiniteIncrement {
  Vector6 deps;      ///< R_m^T (D dt) R_m, lamina order, engineering shear
  Eigen::Matrix3d R; ///< polar rotation of F (t_{n+1})
  double J_n = 1;    ///< det F_n
  double J = 1;      ///< det F
};

/// @return the rotation-free increment of the step F_n -> F (both det > 0)
FiniteIncrement finiteIncrement(const Eigen::Matrix3d& F_n, const Eigen::Matrix3d& F);

/// @return finiteIncrement(F_n, F).deps alone (no rotation at t_{n+1}: one
/// polar decomposition instead of two)
Vector6 rotationFreeIncrement(const Eigen::Matrix3d& F_n, const Eigen::Matrix3d& F);

/// @return R s R^T for a symmetric tensor s in lamina order (tensor components)
Vector6 rotateTensor(const Eigen::Matrix3d& R, const Vector6& s);

/// @return the 3x3 matrix of a stress-like vector (lamina order, tensor components)
Eigen::Matrix3d toMatrix(const Vector6& s);
/// @return the lamina-order vector (tensor components) of a symmetric 3x3 matrix
Vector6 fromMatrix(const Eigen::Matrix3d& m);

/// @return the small strain of F: sym(F - I), lamina order, engineering shear
Vector6 smallStrain(const Eigen::Matrix3d& F);

} // namespace lamina::materials
