#pragma once
/// @file plane_stress_point.hpp
/// @brief Test helper: a material point under equibiaxial in-plane stretch
/// F_p = (1 + e) I_2 stepped through planeStressUpdate, the in-plane
/// increments from finiteIncrement of diag(1 + e, 1 + e, 1) (what a membrane
/// gives the law), the thickness and out-of-plane strain solved.

#include "materials/kinematics.hpp"
#include "materials/plane_stress.hpp"

#include <vector>

namespace lamina::test {

/// [xx, yy, xy] of a lamina-order vector.
inline Eigen::Vector3d inPlane(const materials::Vector6& s) {
  return {s[0], s[1], s[3]};
}

/// The point: its law, state, strain, thickness stretch and driven strain e.
struct BiaxialPoint {
  const materials::ConstitutiveLaw& law;
  std::vector<double> state;
  materials::Vector6 eps = materials::Vector6::Zero();
  double lambda3 = 1, e = 0;
  explicit BiaxialPoint(const materials::ConstitutiveLaw& l)
      : law(l), state(static_cast<std::size_t>(l.stateSize())) {
    law.initState(state.data());
  }
  /// @return the in-plane deformation gradient diag(1 + e, 1 + e, 1)
  static Eigen::Matrix3d F(double e) { return Eigen::Vector3d(1 + e, 1 + e, 1).asDiagonal(); }
  /// @return the step from the current e to @p e_new over @p dt
  materials::PlaneStressStep step(double e_new, double dt) const {
    materials::PlaneStressStep s;
    s.eps_n = eps;
    s.deps_p = inPlane(materials::finiteIncrement(F(e), F(e_new)).deps);
    s.lambda3_n = lambda3;
    s.J2_n = (1 + e) * (1 + e);
    s.J2 = (1 + e_new) * (1 + e_new);
    s.dt = dt;
    return s;
  }
  /// Takes the step to @p e_new and commits it.
  materials::PlaneStressResult advance(double e_new, double dt, bool tangent = false) {
    const materials::PlaneStressResult r =
        materials::planeStressUpdate(law, step(e_new, dt), state.data(), state.data(), tangent);
    eps = r.eps;
    lambda3 = r.lambda3;
    e = e_new;
    return r;
  }
};

} // namespace lamina::test
