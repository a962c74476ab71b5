#pragma once
/// @file fabric_element.hpp
/// @brief The total-Lagrangian constant-strain triangle of the
/// large-deflection fabric membrane, in 3D.
///
/// Reference frame of an element: e3 the unit normal (X2 - X1) x (X3 - X1),
/// e1 the region's material axis projected onto the element plane (as
/// LS-DYNA's AOPT does; the first edge when the axis is normal to the
/// element), e2 = e3 x e1. With the shape-function gradients dN_a in that
/// frame, the deformation gradient (3 x 2) is F = sum_a x_a dN_a^T, the
/// Green-Lagrange strain E = (F^T F - I) / 2, in Voigt form
/// [E11, E22, 2 E12] (engineering shear), the second Piola-Kirchhoff stress
/// S = C_ps E + S0 (S0 the pre-stress), and the nodal internal force
/// f_a = h A0 F S dN_a. Strain energy h A0 (E.C_ps E / 2 + S0.E); for a
/// tension-only element the stored energy of its stress,
/// h A0 (S.C_ps^-1 S - S0.C_ps^-1 S0) / 2 (fabricStoredEnergy()).
///
/// Plane-stress stiffness: with p = {xx, yy, xy} and z = {zz} (lamina
/// order), C_ps = C_pp - C_pz C_zz^-1 C_zp (sigma_zz = 0 condensed out; the
/// transverse shears yz, xz play no part in a tension membrane).
///
/// Tension only (wrinkling), two laws (WrinklingLaw):
/// - relaxed (the default): tension-field theory's relaxed energy
///   (relaxed_wrinkling.hpp): S = C_ps (E + P) + S0 with the stress-free
///   wrinkling strain P >= 0 that minimizes the energy; hyperelastic.
/// - projection: S is replaced by the tensile part of its spectral
///   decomposition, sum_i max(s_i, 0) n_i n_i^T: a wrinkled element carries
///   uniaxial tension along its major principal direction, a slack one
///   nothing. Not the gradient of any energy: its work around a closed
///   strain cycle is not zero (docs/membrane-large-deflection.md).
/// Either way the Cauchy stress F S F^T / J has no compressive principal
/// value (congruence keeps the signs of the eigenvalues).

#include "materials/stiffness.hpp"
#include "membrane/model/mesh.hpp"
#include "membrane/model/relaxed_wrinkling.hpp"
#include "membrane/model/section.hpp"

#include <Eigen/Dense>

#include <array>

namespace lamina::membrane {

/// @return C_ps = C_pp - C_pz C_zz^-1 C_zp of a 6x6 stiffness in lamina order
/// (Pa; rows/columns xx, yy, xy with engineering shear).
Eigen::Matrix3d planeStressStiffness(const materials::Matrix6& C);

/// Reference data of one triangle.
struct FabricElement {
  std::array<int, 3> nodes{};        ///< node indices
  std::array<Eigen::Vector2d, 3> dN; ///< shape-function gradients in the element frame (1/m)
  double area0 = 0;                  ///< reference area (m^2)
  Eigen::Matrix3d frame;             ///< columns e1, e2, e3 of the reference frame
};

/// Kinematics and stress of one element at one configuration.
struct FabricStress {
  Eigen::Matrix<double, 3, 2> F; ///< deformation gradient
  Eigen::Vector3d E;             ///< Green-Lagrange strain [E11, E22, 2 E12]
  Eigen::Vector3d S;             ///< second Piola-Kirchhoff stress [S11, S22, S12] (Pa)
  Wrinkle state = Wrinkle::Taut; ///< wrinkling state (Taut without tension_only)
};

/// Builds the reference data of triangle @p e of @p mesh with material axis @p axis.
FabricElement makeFabricElement(const Mesh& mesh, int e, const Eigen::Vector3d& axis);

/// Evaluates F, E and S at current node positions @p x with the wrinkling law @p wrinkling.
FabricStress fabricStress(const FabricElement& el, const std::array<Eigen::Vector3d, 3>& x,
                          const Eigen::Matrix3d& Cps, const Eigen::Vector3d& S0,
                          WrinklingLaw wrinkling);

/// @return the nodal internal forces (3 x 3, column a = node a) of @p st for thickness @p h.
Eigen::Matrix3d fabricForces(const FabricElement& el, const FabricStress& st, double h);

/// @return the energy per unit reference volume stored in the stress of @p st (J/m^3),
/// relative to the pre-stressed reference: (S.C_ps^-1 S - S0.C_ps^-1 S0) / 2 with
/// @p Cinv = C_ps^-1. The elastic strain C_ps^-1 S carries the stress; the rest of
/// E (the wrinkling strain of a tension-only element) is stress-free and stores
/// nothing. Equals E.C_ps E / 2 + S0.E for a taut element; >= 0 without pre-stress.
/// With the relaxed law it is the relaxed energy W_rel(E), the potential of S;
/// the work of the projection law is not a state function (docs/membrane-large-deflection.md).
double fabricStoredEnergy(const FabricStress& st, const Eigen::Matrix3d& Cinv,
                          const Eigen::Vector3d& S0);

/// @return the principal values (major first) of the symmetric 2x2 [a, c; c, b]
Eigen::Vector2d principal2(double a, double b, double c);

/// @return the principal in-plane Cauchy stresses (major first, Pa) of @p st:
/// the eigenvalues of S C / J with C = F^T F, J = sqrt(det C) (the area ratio;
/// the thickness is taken as constant).
Eigen::Vector2d principalCauchy(const FabricStress& st);

} // namespace lamina::membrane
