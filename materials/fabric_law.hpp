#pragma once
/// @file fabric_law.hpp
/// @brief The warp-and-fill fabric law: two yarn directions that carry no
/// compression and an in-plane shear modulus (the idea of LS-DYNA's fabric
/// material, *MAT_FABRIC / MAT_034, LS-DYNA Theory Manual), as a
/// ConstitutiveLaw for the large-deflection membrane.
///
/// **Axes.** Warp is the law's x axis (a membrane section's `material_axis`
/// on the surface), fill its y axis, z the normal.
///
/// **Stress.** With the law's strain eps (rotation-free frame, lamina order
/// [xx, yy, zz, xy, yz, xz], engineering shear) the Kirchhoff stress tau =
/// J sigma is
///
///     tau_xx = s_warp(eps_xx)      tau_yy = s_fill(eps_yy)     (yarn curves, 0 in compression)
///     tau_xy = G12 gamma_xy
///     tau_zz = E_t eps_zz          tau_yz = G_t gamma_yz       tau_xz = G_t gamma_xz
///
/// and the Cauchy stress sigma = tau / J (J = PointStep::J). s_warp, s_fill
/// are YarnCurve's: E eps for eps > 0 with a modulus, or a tabulated curve.
/// There is no Poisson coupling (nu12 = 0: a woven fabric's yarns are
/// weakly coupled, and with a coupling the cut-off of one yarn would change
/// the other's stress). tau is the gradient of the stored energy per
/// reference volume
///
///     W(eps) = W_warp(eps_xx) + W_fill(eps_yy) + G12 gamma_xy^2 / 2
///              + E_t eps_zz^2 / 2 + G_t (gamma_yz^2 + gamma_xz^2) / 2,
///
/// (W_warp = int_0 s_warp, exact for a piecewise linear curve), so the law is
/// hyperelastic in its strain: the work of tau over any closed strain path
/// is zero, it dissipates nothing, and isHyperelastic() is true.
/// Kirchhoff rather than Cauchy (sigma = s(eps)) because then the work per
/// reference volume, J sigma . d eps = tau . d eps, is the gradient of W;
/// with sigma = s(eps) the factor J, which depends on both yarn strains,
/// would make biaxial work path dependent. At small strain (J ~ 1) the two
/// agree.
///
/// **Transverse terms.** E_t = G_t = kFabricTransverseFraction times the
/// largest in-plane modulus (the steepest yarn slope or G12): small and
/// positive so that the 3D stiffness is positive definite and plane-stress
/// condensation well posed. Nothing couples them with the in-plane strains,
/// so sigma_zz = sigma_yz = sigma_xz = 0 holds at eps_zz = gamma_yz =
/// gamma_xz = 0 whatever the in-plane strain: the condensed in-plane
/// response is exactly the fabric's, the thickness does not change
/// (lambda3 = 1), and the plane-stress Newton (plane_stress.hpp) has
/// nothing to correct after its predictor.
///
/// **Tangent** d sigma / d eps at fixed J: diag(s_warp', s_fill', E_t, G12,
/// G_t, G_t) / J, the yarn slopes 0 in compression (eps <= 0).
/// **Instantaneous stiffness** (elasticStiffness(J), the stable step):
/// diag(max slope warp, max slope fill, E_t, G12, G_t, G_t) / J.
/// **State**: one double, W at the last update (per reference volume), so
/// that storedEnergy() = W / J per current volume is exact on a flat part of
/// a curve, where the stress does not determine the strain.

#include "materials/law.hpp"
#include "materials/yarn_curve.hpp"

namespace lamina::core {
class TableReader;
}

namespace lamina::materials {

/// E_t / max in-plane modulus and G_t / max in-plane modulus (see the file comment).
inline constexpr double kFabricTransverseFraction = 1e-3;

/// The parameters of a fabric law.
struct FabricParameters {
  YarnCurve warp = YarnCurve::linear(1.0); ///< warp yarn (law x), Pa
  YarnCurve fill = YarnCurve::linear(1.0); ///< fill yarn (law y), Pa
  double G12 = 1.0;                        ///< in-plane shear modulus (Pa)
  /// @return E_t = G_t, the transverse modulus (Pa)
  double transverseModulus() const;
};

/// Reads the fabric keys of @p t: per direction (warp, fill) a modulus
/// `E_warp` / `E_fill` (Pa) or a curve `warp_curve` / `fill_curve` (a CSV
/// file relative to @p t's file; yarn_curve.hpp), exactly one of the two;
/// `G12` (Pa); optional `nu12`, which must be 0. Throws lamina::Error naming
/// the key for a missing, non-positive or non-finite modulus, both a modulus
/// and a curve, a non-zero nu12, and a bad curve file (with its line).
FabricParameters readFabricParameters(const core::TableReader& t);

/// The fabric law of one parameter set (see the file comment).
class FabricLaw final : public ConstitutiveLaw {
public:
  /// Layout of the state (doubles per point).
  static constexpr int kEnergy = 0; ///< W at the last update (J per reference m^3)
  /// @param p the yarn curves and G12
  explicit FabricLaw(FabricParameters p);
  LawKind kind() const override { return LawKind::Fabric; }
  bool isLinear() const override { return false; }
  bool isHyperelastic() const override { return true; }
  int stateSize() const override { return 1; }
  void initState(double* state) const override { state[kEnergy] = 0; }
  Stiffness elasticStiffness(double J = 1.0) const override;
  void update(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
              Matrix6* tangent) const override;
  /// W / J (J/m^3 of current volume) with W from @p state (required).
  double storedEnergy(const Vector6& sigma, const double* state, double J) const override;
  /// Membrane plane stress with no free direction: nothing couples the
  /// transverse terms with the in-plane strains (file comment), so the
  /// Newton of planeStressUpdate() stops at its predictor, which is z = 0
  /// (the out-of-plane strains and the thickness of t_n kept). This takes
  /// that step and its convergence test without the Newton's stiffness,
  /// LU and tangent; a step the test refuses, or one with free directions
  /// (wrinkling), is declined and gets the Newton. The same numbers as the
  /// Newton's (up to the sign of a zero).
  bool planeStressStep(const PlaneStressStep& step, const double* state_n, double* state,
                       double tolerance, PlaneStressResult& out) const override;
  /// @return W(@p eps) per reference volume (J/m^3; see the file comment)
  double energy(const Vector6& eps) const;
  /// @return the parameters
  const FabricParameters& parameters() const { return p_; }

private:
  FabricParameters p_;
  double Et_; ///< E_t = G_t (Pa)
};

} // namespace lamina::materials
