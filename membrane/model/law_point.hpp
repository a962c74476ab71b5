#pragma once
/// @file law_point.hpp
/// @brief One element of the large-deflection membrane whose section holds a
/// nonlinear constitutive law (GVBO, a reduced-order cell): its history and
/// one step of it.
///
/// **Kinematics.** The element's deformation gradient F (3 x 2, from its
/// reference frame to space, fabric_element.hpp) is completed by the current
/// unit normal n to F3 = [F | n]. The step F3_n -> F3 is taken by
/// materials::finiteIncrement (Hughes-Winget midpoint in the Green-Naghdi
/// frame, polyurea chapter eq. 5), so the law sees its strain in the
/// rotation-free frame, i.e. in the element's material axes (e1 the
/// section's axis projected, e2, e3 the normal). Its in-plane part (xx, yy,
/// xy) is imposed; the out-of-plane strains (zz, yz, xz) are found so that
/// sigma_zz = sigma_yz = sigma_xz = 0 (membrane plane stress, a local Newton
/// in materials::planeStressUpdate), and the thickness follows the
/// out-of-plane stretch lambda3: h = lambda3 h0 and J = J2 lambda3 (J2 the
/// area ratio).
///
/// **Force.** With F = R2 U2 (R2 the first two columns of the polar
/// rotation of F3, U2 = R2^T F symmetric 2 x 2) and the in-plane Cauchy
/// stress sigma_hat of the law's frame, the second Piola-Kirchhoff stress is
/// S = J U2^-1 sigma_hat U2^-1 and the nodal forces are h0 A0 F S dN_a, as
/// for an elastic element.
///
/// **Wrinkling** (tension_only) composes with any law: when the law's
/// in-plane stress has a compressive principal value, part of the in-plane
/// strain is taken by wrinkles, a stress-free wrinkling strain
/// eps_w = -a d, d = n2 (x) n2 along the compressive principal direction
/// n2, with a such that d . sigma = 0 (uniaxial tension along n1); when the
/// remaining principal stress is not tensile either, the element is slack
/// (eps_w takes the whole in-plane strain, sigma = 0). The law sees the
/// strain minus eps_w, so its state stays consistent; eps_w is not
/// accumulated (each step releases the previous one and solves it again).
/// Wrinkles do not compress the material: the law's area ratio is the
/// element's J2 times (2 - tr eps_w)/(2 + tr eps_w) (the midpoint rule's
/// exp(-tr eps_w)), found by solving twice, and J = that times lambda3 is
/// both the law's volume ratio and the one in S below.
///
/// **Energy** per unit reference volume: the work of the stress over the
/// law's strain by the trapezoidal rule, w += (J_n sigma_n + J sigma) .
/// d eps / 2; the stored part psi = J law.storedEnergy(sigma, state, J);
/// the inelastic dissipation D += dw - (psi - psi_n). The equivalent
/// inelastic strain accumulates sqrt(2/3 e:e) of the deviator e of
/// d eps - C(J)^-1 (sigma - sigma_n) (C the law's instantaneous stiffness).
/// A hyperelastic law (law.isHyperelastic(), the fabric law) stores all its
/// work: D and the inelastic strain stay zero (the trapezoidal work would
/// differ from psi - psi_n by the rule's error only).

#include "materials/law.hpp"

#include <Eigen/Dense>

namespace lamina::membrane {

/// Layout of an element's history block (doubles); the law's state follows at kLaw.
struct LawPoint {
  static constexpr int kF = 0;        ///< F at t_n, 3 x 2 column-major (6)
  static constexpr int kEps = 6;      ///< the law's strain at t_n (6, lamina order)
  static constexpr int kLambda3 = 12; ///< thickness stretch h / h0
  static constexpr int kWrinkle = 13; ///< wrinkling strain [xx, yy, xy] (3)
  static constexpr int kSigma = 16;   ///< in-plane Cauchy stress [xx, yy, xy], law frame (3, Pa)
  static constexpr int kJ = 19;       ///< volume ratio J = J2 lambda3
  static constexpr int kPsi = 20;     ///< stored energy per reference volume (J/m^3)
  static constexpr int kDissipation = 21;   ///< inelastic dissipation per reference volume (J/m^3)
  static constexpr int kInelastic = 22;     ///< equivalent inelastic strain
  static constexpr int kInelasticRate = 23; ///< its rate over the last step (1/s)
  static constexpr int kWrinkleState = 24;  ///< 0 taut, 1 wrinkled, 2 slack (as Wrinkle)
  static constexpr int kLaw = 25;           ///< the law's state (law.stateSize())
  /// @return doubles per element for @p law
  static int size(const materials::ConstitutiveLaw& law) { return kLaw + law.stateSize(); }
};

/// Writes the virgin history of an element whose reference F is @p F0 (the
/// first two columns of its frame) into @p block.
void initLawPoint(const materials::ConstitutiveLaw& law, const Eigen::Matrix<double, 3, 2>& F0,
                  double* block);

/// One step of an element to deformation gradient @p F over @p dt: reads
/// @p block_n, writes @p block (must not alias it) and returns the second
/// Piola-Kirchhoff stress [S11, S22, S12] (Pa) at t_{n+1}. Throws
/// lamina::Error when the element is degenerate (F of rank < 2), the local
/// Newton does not converge or the stress is not finite (the caller names
/// the element and the time).
Eigen::Vector3d stepLawPoint(const materials::ConstitutiveLaw& law,
                             const Eigen::Matrix<double, 3, 2>& F, bool tension_only, double dt,
                             const double* block_n, double* block);

/// What one step of an element ends in: everything storeLawPoint writes.
struct LawPointEnd {
  const double* F = nullptr;     ///< F at t_{n+1}, 3 x 2 column-major (6)
  const double* eps = nullptr;   ///< the law's strain at t_{n+1} (6, lamina order)
  double lambda3 = 1;            ///< thickness stretch
  const double* eps_w = nullptr; ///< wrinkling strain [xx, yy, xy] (3)
  double sigma[3] = {};          ///< in-plane Cauchy stress [xx, yy, xy], law frame (Pa)
  double J = 1;                  ///< volume ratio
  double psi = 0;                ///< stored energy per reference volume (J/m^3)
  double dissipated = 0;         ///< the step's dissipation per reference volume (J/m^3)
  double inelastic = 0;          ///< the step's equivalent inelastic strain
  double state = 0;              ///< 0 taut, 1 wrinkled, 2 slack (as Wrinkle)
};

/// Writes the history at t_{n+1} of a step over @p dt that ended in @p end
/// into @p block, accumulating the dissipation and inelastic strain of
/// @p block_n (stepLawPoint's last part; law_lanes.cpp's too).
void storeLawPoint(const LawPointEnd& end, double dt, const double* block_n, double* block);

/// @return the equivalent (von Mises) value sqrt(2/3 e:e) of the deviator
/// e of the engineering strain @p d
double equivalentDeviatoric(const materials::Vector6& d);

/// @return S = J U2^-1 sigma_hat U2^-1 [S11, S22, S12] of the history @p block at
/// deformation gradient @p F (the one the block was stepped to)
Eigen::Vector3d lawPointPk2(const Eigen::Matrix<double, 3, 2>& F, const double* block);

} // namespace lamina::membrane
