#pragma once
/// @file plane_stress.hpp
/// @brief One step of any 3D ConstitutiveLaw under membrane plane stress,
/// with mixed in-plane control (imposed strain, or free directions whose
/// amplitude is unknown and whose stress vanishes: wrinkling).
///
/// **The step.** The caller imposes the in-plane strain increment deps_p =
/// [xx, yy, xy] (engineering shear) in the law's rotation-free frame, the
/// in-plane area ratios J2_n, J2 and dt. The unknowns are
///
///     z = (deps_zz, deps_yz, deps_xz; a_1 .. a_nf),
///
/// the out-of-plane strain increments and the amplitudes of the nf free
/// directions d_k (engineering-strain Voigt [xx, yy, xy]). The law is
/// stepped with PointStep{eps_n, eps_n + deps, J_n, J, dt}, where deps holds
/// deps_p + sum_k a_k d_k in the xx, yy, xy slots and the unknowns in zz, yz,
/// xz. The thickness stretch follows the midpoint (Hughes-Winget) rule that
/// finiteIncrement() gives for a diagonal stretch,
///
///     deps_zz = (lambda3 - lambda3_n) / ((lambda3 + lambda3_n) / 2),
///     i.e. lambda3 = lambda3_n (2 + deps_zz) / (2 - deps_zz),
///
/// and J_n = J2_n lambda3_n, J = J2 lambda3: J changes with the unknown
/// deps_zz. The equations are
///
///     sigma_zz = sigma_yz = sigma_xz = 0,    d_k . sigma_p = 0  (k = 1..nf),
///
/// sigma_p = [sigma_xx, sigma_yy, sigma_xy]: with B the 6 x (3 + nf) matrix
/// whose columns are the unit vectors of zz, yz, xz and the d_k placed in the
/// xx, yy, xy slots, deps = E_p deps_p + B z and the equations read B^T sigma
/// = 0 (E_p places [xx, yy, xy] in lamina order).
///
/// **Method.** Predictor: the elastic condensation with C0 =
/// law.elasticStiffness(J_n), z0 = -(B^T C0 B)^-1 B^T C0 E_p deps_p (exact
/// for a linear law whose state at t_n satisfies the constraints). Newton
/// with the law's consistent tangent T: z <- z - (B^T T B)^-1 B^T sigma. The
/// tangent of a law that holds J fixed (GVBO, gvbo_law.hpp) leaves out the
/// change of the moduli with J through lambda3, so the convergence can be
/// linear (ratio about |d ln K / d ln J| |deps_zz|: fast for the small
/// volume changes of one step). A Newton step that would take |deps_zz|
/// beyond 1.5 (a thickness ratio beyond 7 in one step) is halved until it
/// does not. Converged when
///
///     max(|sigma_zz|, |sigma_yz|, |sigma_xz|, |d_k . sigma_p| / |d_k|)
///         <= tolerance * max(max|sigma|, max|C0| max(|eps_n|, |eps|))
///
/// (max norms; |d_k| Euclidean): the second term is the size of the stress
/// terms the law sums (its instantaneous stiffness times the strain), the
/// scale of their round-off. It keeps the test meaningful where the stress
/// passes through zero (unloading, all directions free), where a test
/// relative to |sigma| alone would ask for less than round-off. With the
/// default 1e-12 the residual is ~1e-12 of the stress scale (K/E ~ 20 times
/// that of |sigma| for a nearly incompressible polymer), three to four orders
/// of magnitude above the round-off of those terms (~1e-16 times a few
/// of them) and four below the 1e-8 to which a membrane is compared with
/// `materials drive`. After kPlaneStressMaxIterations iterations the step
/// is refused with lamina::Error giving the residual (the caller adds the
/// element and the time).
///
/// **A law's own step.** When no tangent is asked, a law may take the step
/// itself (ConstitutiveLaw::planeStressStep), to the same test on the
/// constrained stresses; the isotropic GVBO law does so with no free
/// direction and no transverse shear (one Newton on deps_zz and its
/// overstress invariant together: a third of the work of a Newton on its
/// update, which solves the overstress equation anew at every iterate); the
/// fabric law (fabric_law.hpp) with no free direction, where the Newton
/// would stop at its predictor (its transverse terms are uncoupled): one
/// update and the test. A law that declines gets the Newton above.
///
/// **Linear laws** (law.isLinear()): closed form, no iteration, sigma = C eps
/// with z = -(B^T C B)^-1 B^T C (eps_n + E_p deps_p) (the constraints hold at
/// t_{n+1} whatever eps_n holds).
///
/// **Condensed tangent.** Differentiating B^T sigma(E_p eps_p + B z) = 0 at
/// the converged point, dz = -(B^T T B)^-1 B^T T E_p d eps_p, so
///
///     d sigma_p / d eps_p = T_pp - E_p^T T B (B^T T B)^-1 B^T T E_p,
///
/// which with no free directions is T_pp - T_pc T_cc^-1 T_cp (c = zz, yz,
/// xz) and, for a linear isotropic law, the plane-stress stiffness C_ps. It
/// maps every free direction to zero and is zero on them (d_k^T T_ps = 0,
/// T_ps d_k = 0). It leaves out what the law's tangent leaves out (d/dJ).
///
/// **Cost.** A linear law: one solve of order 3 + nf. A law's own step:
/// what the law says (GVBO: about three iterates, each one evaluation of
/// its moduli and of its overstress equation; fabric: one update). Otherwise one
/// elasticStiffness(J_n), then per iteration one law update with tangent
/// and one LU of order 3 + nf; no heap allocation, except one copy of the
/// state when @p state aliases @p state_n.

#include "materials/law.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>

namespace lamina::materials {

/// Largest |deps_zz| of one Newton iterate (a thickness ratio of 7 in one step).
inline constexpr double kMaxThicknessIncrement = 1.5;

/// @return lambda3 at t_{n+1} from the midpoint rule (file comment)
inline double midpointThicknessStretch(double lambda3_n, double deps_zz) {
  return lambda3_n * (2 + deps_zz) / (2 - deps_zz);
}

/// @return the stress scale of the convergence test (file comment):
/// max(max|sigma|, maxC0 max(max|eps_n|, max|eps|)), maxC0 = max|C0|
inline double planeStressScale(const Vector6& sigma, double maxC0, const Vector6& eps_n,
                               const Vector6& eps) {
  return std::max(sigma.cwiseAbs().maxCoeff(),
                  maxC0 * std::max(eps_n.cwiseAbs().maxCoeff(), eps.cwiseAbs().maxCoeff()));
}

/// Default tolerance of planeStressUpdate (see the file comment).
inline constexpr double kPlaneStressTolerance = 1e-12;
/// Newton iterations before a plane-stress step is refused: room for the
/// linear convergence of a law whose tangent holds J fixed.
inline constexpr int kPlaneStressMaxIterations = 50;

/// One plane-stress step (see the file comment).
struct PlaneStressStep {
  /// the law's strain at t_n, all six (rotation-free frame, lamina order, engineering shear)
  Vector6 eps_n = Vector6::Zero();
  /// imposed in-plane increment [xx, yy, xy] (engineering)
  Eigen::Vector3d deps_p = Eigen::Vector3d::Zero();
  double lambda3_n = 1;    ///< thickness stretch at t_n (> 0)
  double J2_n = 1, J2 = 1; ///< in-plane area ratios at t_n, t_{n+1} (J = J2 * lambda3)
  double dt = 0;           ///< s
  int n_free = 0;          ///< 0..3 in-plane directions whose amplitude is unknown (wrinkling)
  /// d_k (engineering-strain Voigt [xx, yy, xy]); the first n_free are used
  /// and must be linearly independent
  std::array<Eigen::Vector3d, 3> free_dir{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::Zero()};
};

/// What one plane-stress step computes.
struct PlaneStressResult {
  /// the law's strain at t_{n+1}, incl. the solved out-of-plane part
  Vector6 eps = Vector6::Zero();
  double lambda3 = 1; ///< thickness stretch at t_{n+1}
  /// Cauchy stress (zz, yz, xz ~ 0 to the tolerance), rotation-free frame, Pa
  Vector6 sigma = Vector6::Zero();
  /// condensed consistent tangent d sigma_p / d eps_p (Pa), only if asked
  Eigen::Matrix3d tangent = Eigen::Matrix3d::Zero();
  std::array<double, 3> amplitude{}; ///< a_k of the free directions
  int iterations = 0;                ///< Newton iterations (0 for a linear law)
  double residual = 0;               ///< final max constrained stress (Pa, scaled as in the test)
};

/// @return the law's strain at t_{n+1} of @p step with the normal strain
/// increment @p deps_zz and no transverse shear increment: eps_n + (deps_xx,
/// deps_yy, deps_zz, deps_xy, 0, 0), lamina order (a law's own step without
/// free directions).
inline Vector6 strainAtEnd(const PlaneStressStep& step, double deps_zz) {
  return step.eps_n + Vector6(step.deps_p[0], step.deps_p[1], deps_zz, step.deps_p[2], 0.0, 0.0);
}

/// Newton on the unknowns z = (eps_zz, eps_yz, eps_xz at t_{n+1}; a_1..a_n_free)
/// so that sigma_zz = sigma_yz = sigma_xz = 0 and d_k . sigma_p = 0, with the
/// in-plane increment deps_p + sum_k a_k d_k (file comment). Reads @p state_n,
/// writes the law's state at t_{n+1} to @p state (law.stateSize() doubles; may
/// alias state_n). @p want_tangent: fill PlaneStressResult::tangent. Throws
/// lamina::Error on a bad step (n_free out of 0..3, dependent free
/// directions, lambda3_n or J2 not positive), a non-finite stress, or no
/// convergence within kPlaneStressMaxIterations (the message gives the
/// residual); a law's error passes through.
PlaneStressResult planeStressUpdate(const ConstitutiveLaw& law, const PlaneStressStep& step,
                                    const double* state_n, double* state, bool want_tangent,
                                    double tolerance = kPlaneStressTolerance);

} // namespace lamina::materials
