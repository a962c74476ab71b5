#pragma once
/// @file fabric_lanes.hpp
/// @brief The nodal forces of kFabricLanes elements of one linear section at
/// once: the elastic fabric element (fabric_element.hpp) vectorized across
/// elements.
///
/// Per lane: F = sum_a x_a dN_a^T (x_a = X_a + u_a, the positions), E = (F^T F - I)/2,
/// S = C_ps E + S0 and f_a = h A0 F S dN_a, each sum taken in the order of
/// the one-element force (LargeDeflection's element loop), and this file and
/// large_deflection.cpp are compiled without contracting a product and a sum
/// into one fused operation, so every lane's force equals the one-element
/// force bit for bit on any CPU (tests/membrane/fabric_lanes_test.cpp). With the relaxed
/// wrinkling law a lane whose trial stress is not positive semidefinite is
/// handed back: the caller takes it through relaxedStress().

#include <cstdint>

namespace lamina::membrane {

/// Elements per group.
inline constexpr int kFabricLanes = 8;

/// A group's elements as the lanes read them, one column per lane.
struct FabricLaneGroup {
  std::int32_t node[3][kFabricLanes]; ///< 3 x the node index of each corner (its first dof)
  double dN[6][kFabricLanes];         ///< dN_a in the element frame: x0, y0, x1, y1, x2, y2 (1/m)
  double hA[kFabricLanes];            ///< thickness x reference area (m^3)
};

/// A linear section's law: S = C E + S0.
struct LinearLaneLaw {
  double C[3][3];       ///< plane-stress stiffness C_ps, row-major (Pa)
  double s0[3];         ///< pre-stress per thickness [S11, S22, S12] (Pa)
  bool relaxed = false; ///< the relaxed wrinkling law: hand back a stress not taut
};

/// The nodal forces of every lane of @p g at the positions @p x (3 per
/// node), node a's x, y, z at f[3 a + c][lane] (N).
/// @return the mask of the lanes taken (bit l for lane l): all of them
/// unless @p law is relaxed; the others' f is meaningless
std::uint32_t linearFabricForces(const LinearLaneLaw& law, const FabricLaneGroup& g,
                                 const double* x, double (&f)[9][kFabricLanes]);

/// What the stable step of a linear section reads besides its law.
struct LaneWave {
  double modulus = 0; ///< the largest wave modulus of C_ps (Pa)
  double density = 0; ///< mass density (kg/m^3)
  double rest = 0;    ///< the speed at rest (m/s), the least the step assumes
};

/// Each lane's stable step: its length over the speed of its fastest wave,
/// sqrt((M lambda_max^2 + the largest principal S) / rho) with M the
/// largest wave modulus and lambda_max^2 the larger of 1 and the major
/// value of C = F^T F, or over the rest speed if that is larger
/// (LargeDeflection::linearStableStep, whose formulas the lanes repeat).
/// @param length the lanes' element lengths (m)
/// @param dt out: the lanes' stable steps (s)
/// @return the mask of the lanes taken: all of them unless @p law is
/// relaxed (a stress not taut is relaxed first by the caller)
std::uint32_t linearFabricStableSteps(const LinearLaneLaw& law, const LaneWave& wave,
                                      const FabricLaneGroup& g, const double* x,
                                      const double* length, double (&dt)[kFabricLanes]);

} // namespace lamina::membrane
