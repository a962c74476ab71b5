#pragma once
/// @file relaxed_wrinkling.hpp
/// @brief Tension-field theory's relaxed energy of a linear (Saint
/// Venant-Kirchhoff) membrane law: the conservative wrinkling law of the
/// large-deflection fabric (`tension_only = true`, `wrinkling = "relaxed"`).
///
/// Wrinkles make the mean surface shorter than the material: the material
/// (elastic) strain is the mean-surface Green strain E plus a stress-free
/// wrinkling strain P, positive semidefinite (P = w n n^T, w >= 0, takes up
/// the compressive strain along n). With the law W(E) = E.C E / 2 + S0.E
/// (C = C_ps, S0 the pre-stress), the relaxed energy is
///
///     W_rel(E) = min over P >= 0 of W(E + P)
///
/// (A. C. Pipkin, "The relaxed energy density for isotropic elastic
/// membranes", IMA J. Appl. Math. 36 (1986): the relaxed energy defined as
/// the least energy over the wrinkled states of the same mean surface; the
/// equation number was not at hand. The same minimization for an
/// anisotropic C.) Writing Et = E + C^-1 S0 (the
/// strain from the stress-free state), W(E + P) = Q(Et + P) - Q(C^-1 S0) with
/// Q(x) = x.C x / 2 strictly convex, so the minimizer is unique, and it is
/// the one point of the KKT conditions: S = C (Et + P) positive semidefinite,
/// P positive semidefinite, S : P = 0. Three states:
/// - taut: S(Et) = C Et positive semidefinite, P = 0;
/// - slack: Et negative semidefinite (both principal strains from the
///   stress-free state <= 0), P = -Et, S = 0;
/// - wrinkled: otherwise, P = w n n^T of rank one with S n = 0, S >= 0
///   (uniaxial tension across the wrinkles).
/// In the wrinkled state, for a direction n(theta) the best amplitude is
/// w = -(n n : C Et) / (n n : C : n n) when positive, and W drops by
/// (n n : C Et)^2 / (2 n n : C : n n); the best theta makes S n = 0. For an
/// isotropic C, n is the minor principal direction of Et and S is uniaxial
/// with S1 = E_Y e1 (e1 the major principal strain from the stress-free
/// state): Pipkin's closed form. For an anisotropic C, a 1D search: samples
/// of the drop over the directions that are in compression (or over all
/// directions when every one is), then a bracketed root of the stationarity
/// condition m.S n = 0 (m perpendicular to n) to round-off, checked against
/// the KKT conditions (a dense search when they fail).
///
/// By the envelope theorem S = C (Et + P) is the exact gradient of W_rel:
/// the law is hyperelastic, its work around a closed strain cycle is zero
/// and the stored energy (S.C^-1 S - S0.C^-1 S0) / 2 is its potential.

#include <Eigen/Dense>

namespace lamina::membrane {

/// Wrinkling state of an element.
enum class Wrinkle : int {
  Taut = 0,     ///< both principal stresses >= 0
  Wrinkled = 1, ///< uniaxial tension: one principal stress zero (relaxed) or removed (projection)
  Slack = 2,    ///< no stress
};

/// The relaxed stress at one strain, with the wrinkling strain that gives it.
struct RelaxedStress {
  Eigen::Vector3d S = Eigen::Vector3d::Zero(); ///< [S11, S22, S12] = C (Et + P) (Pa)
  Wrinkle state = Wrinkle::Taut;               ///< taut, wrinkled or slack
  /// The wrinkling strain P [P11, P22, 2 P12] (>= 0; w n n^T when wrinkled, -Et when slack)
  Eigen::Vector3d P = Eigen::Vector3d::Zero();
  double w = 0;                                ///< wrinkling amplitude when wrinkled
  Eigen::Vector2d n = Eigen::Vector2d::Zero(); ///< unit wrinkle direction (the stress-free one)
};

/// @return whether the symmetric 2x2 [a, c; c, b] is positive semidefinite
inline bool positiveSemidefinite2(double a, double b, double c) {
  return a >= 0 && b >= 0 && a * b >= c * c;
}

/// @return the relaxed stress at strain @p Et = E + C^-1 S0 ([E11, E22, 2 E12],
/// engineering shear, from the stress-free state) for the plane-stress
/// stiffness @p C (symmetric positive definite, Pa); @p St = C Et, the trial
/// stress (Pa). Taut elements cost one 2x2 semidefiniteness check.
RelaxedStress relaxedStress(const Eigen::Vector3d& St, const Eigen::Vector3d& Et,
                            const Eigen::Matrix3d& C);

/// @return W_rel(E) (J/m^3) at Green strain @p E for stiffness @p C and
/// pre-stress @p S0 (Pa): W(E + P) = (E + P).C (E + P) / 2 + S0.(E + P) at
/// the minimizing P of relaxedStress()
double relaxedEnergy(const Eigen::Vector3d& E, const Eigen::Matrix3d& C, const Eigen::Vector3d& S0);

} // namespace lamina::membrane
