#pragma once
/// @file gvbo_law.hpp
/// @brief The GVBO law (generalized viscoplasticity based on overstress,
/// polyurea chapter section 2, eqs. 3-17, Table 1) at a material point,
/// integrated by backward Euler with its consistent tangent.
///
/// Variables, all in the rotation-free frame (eq. 5): Cauchy stress sigma =
/// p 1 + s, equilibrium stress g and kinematic stress f (deviatoric), the
/// isotropic stress A (scalar). Over a step with strain increment de (its
/// deviator de', trace dth), time step dt and moduli at J_{n+1}
/// (lambda, G, E by eqs. 13-16, K = lambda + 2G/3):
///
///     p     = p_n + K dth                                   (eq. 3, D^in deviatoric)
///     s     = s_n + 2G de' - 3G phi x,  phi = dt / (E k)     (eqs. 3, 6)
///     f     = f_n + Et' phi x,  Et' = 2/3 Et / (1 - Et/E)    (eq. 11)
///     g     = g_n + c (s - s_n + E phi x - beta (g - f))
///             + (1 - c)(f - f_n),  c = psi / E, beta = Gamma E phi / A   (eq. 9)
///     A     = A_n + Ac (Af - A) Gamma phi                     (eq. 12)
///     x     = s - g,  Gamma = sqrt(2/3 x : x)                 (eq. 8)
///     psi   = a1 + (a2 - a1) exp(-a3 Gamma)                   (eq. 10)
///     k     = k1 (1 + Gamma / k2')^-k4,  k2' = k2 + k3 (E - E0)/(Em - E0)   (eq. 17)
///
/// with every unknown at t_{n+1}. Eliminating s, g, f and A leaves the
/// overstress x = W / D along a known tensor W(Gamma) and one scalar
/// equation Gamma D(Gamma) = sqrt(2/3) |W(Gamma)|, solved by a safeguarded
/// Newton iteration (bisection fallback). Backward Euler is L-stable: any dt
/// is stable, and a large dt relaxes the overstress towards zero.
///
/// The tangent is consistent with this update for a fixed J_{n+1}: the
/// derivative of the moduli with respect to J (through the volumetric
/// strain) is left out, a term of relative size |p| ln-derivative of the
/// moduli times the volumetric increment of one step.

#include "materials/gvbo.hpp"
#include "materials/law.hpp"

namespace lamina::materials {

/// Layout of the GVBO state (doubles per point).
struct GvboState {
  static constexpr int kSigma = 0;  ///< Cauchy stress, 6 (lamina order, Pa)
  static constexpr int kG = 6;      ///< equilibrium stress g, 6 (deviatoric)
  static constexpr int kF = 12;     ///< kinematic stress f, 6 (deviatoric)
  static constexpr int kA = 18;     ///< isotropic stress A (Pa)
  static constexpr int kGamma = 19; ///< overstress invariant Gamma of the last step (Pa)
  static constexpr int kSize = 20;  ///< total
};

/// Everything one GVBO step computes besides the stress (for tests and output).
struct GvboStepInfo {
  double Gamma = 0;   ///< overstress invariant at t_{n+1} (eq. 8)
  double k = 0;       ///< viscosity function at t_{n+1} (eq. 17), s
  double psi = 0;     ///< shape function (eq. 10), Pa
  double E = 0;       ///< Young's modulus E[J_{n+1}] (eq. 16), Pa
  int iterations = 0; ///< scalar Newton iterations
};

/// The GVBO law of one parameter set.
class GvboLaw final : public ConstitutiveLaw {
public:
  /// @param p the 15 parameters (chapter Table 1, SI); validated here
  explicit GvboLaw(const GvboParameters& p);
  LawKind kind() const override { return LawKind::Gvbo; }
  bool isLinear() const override { return false; }
  int stateSize() const override { return GvboState::kSize; }
  void initState(double* state) const override;
  Stiffness elasticStiffness(double J = 1.0) const override;
  /// Isotropic compliance at the moduli of J (eqs. 13-16): the deviator over
  /// 2G (engineering shear over G), the mean stress over 3K, K = lambda + 2G/3.
  Vector6 elasticStrain(const Vector6& sigma, double J) const override;
  void update(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
              Matrix6* tangent) const override;
  /// Membrane plane stress (plane_stress.hpp) with no free direction and no
  /// transverse shear in the state or the strain (what a membrane's isotropic
  /// GVBO element holds): one Newton on the normal strain increment and the
  /// overstress invariant together, the moduli at J of each iterate,
  /// converged when sigma_zz meets planeStressUpdate's test and Gamma the
  /// test of update(). Returns false, writing nothing, for any other step,
  /// and when an iterate leaves Gamma >= 0, meets a non-finite value or a
  /// singular Jacobian, or no iterate converges within
  /// kPlaneStressMaxIterations: planeStressUpdate() then runs its Newton.
  bool planeStressStep(const PlaneStressStep& step, const double* state_n, double* state,
                       double tolerance, PlaneStressResult& out) const override;
  /// As update(), also reporting Gamma, k, psi, E and iterations in @p info.
  void updateWithInfo(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
                      Matrix6* tangent, GvboStepInfo* info) const;
  /// @return the parameters
  const GvboParameters& parameters() const { return p_; }

  /// Viscosity function k[Gamma, J] (eq. 17), s.
  double viscosity(double Gamma, double J) const;
  /// Shape function psi[Gamma] (eq. 10), Pa.
  double shape(double Gamma) const;
  /// Et' = 2/3 Et / (1 - Et / E[J]) (eq. 11), Pa.
  double kinematicModulus(double J) const;

private:
  GvboParameters p_;
};

} // namespace lamina::materials
