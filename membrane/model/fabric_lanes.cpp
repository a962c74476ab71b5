#include "membrane/model/fabric_lanes.hpp"

#include "core/vector_clones.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::membrane {

namespace {

constexpr int W = kFabricLanes;

/// Lane @p l of @p g at positions @p x: the columns F0, F1 of F, C = F^T F
/// as [C11, C22, C12] and S = C_ps E + S0; @return whether S is taut (or
/// the law is not relaxed). Every sum is written in the order of the
/// one-element force (LargeDeflection::deformation and linearStress).
LAMINA_CLONE_INLINE core::LaneMask laneStress(const LinearLaneLaw& law, const FabricLaneGroup& g,
                                              const double* x, int l, double (&F0)[3],
                                              double (&F1)[3], double (&C)[3], double (&S)[3]) {
  const std::int32_t i0 = g.node[0][l], i1 = g.node[1][l], i2 = g.node[2][l];
  const double d0 = g.dN[0][l], d1 = g.dN[1][l], d2 = g.dN[2][l], d3 = g.dN[3][l], d4 = g.dN[4][l],
               d5 = g.dN[5][l];
  // 0 + ...: the one-element sums start from zero
  F0[0] = ((0.0 + x[i0] * d0) + x[i1] * d2) + x[i2] * d4;
  F0[1] = ((0.0 + x[i0 + 1] * d0) + x[i1 + 1] * d2) + x[i2 + 1] * d4;
  F0[2] = ((0.0 + x[i0 + 2] * d0) + x[i1 + 2] * d2) + x[i2 + 2] * d4;
  F1[0] = ((0.0 + x[i0] * d1) + x[i1] * d3) + x[i2] * d5;
  F1[1] = ((0.0 + x[i0 + 1] * d1) + x[i1 + 1] * d3) + x[i2 + 1] * d5;
  F1[2] = ((0.0 + x[i0 + 2] * d1) + x[i1 + 2] * d3) + x[i2 + 2] * d5;
  C[0] = F0[0] * F0[0] + F0[1] * F0[1] + F0[2] * F0[2];
  C[1] = F1[0] * F1[0] + F1[1] * F1[1] + F1[2] * F1[2];
  C[2] = F0[0] * F1[0] + F0[1] * F1[1] + F0[2] * F1[2];
  const double E0 = 0.5 * (C[0] - 1), E1 = 0.5 * (C[1] - 1), E2 = C[2];
  S[0] = law.C[0][0] * E0 + law.C[0][1] * E1 + law.C[0][2] * E2 + law.s0[0];
  S[1] = law.C[1][0] * E0 + law.C[1][1] * E1 + law.C[1][2] * E2 + law.s0[1];
  S[2] = (law.C[2][0] * E0 + (law.C[2][1] * E1 + law.C[2][2] * E2)) + law.s0[2];
  // positiveSemidefinite2 (relaxed_wrinkling.hpp), without short circuits
  const core::LaneMask relaxed = law.relaxed;
  return (relaxed == 0) | ((S[0] >= 0) & (S[1] >= 0) & (S[0] * S[1] >= S[2] * S[2]));
}

/// @return the bits of the lanes whose flag is set
LAMINA_CLONE_INLINE std::uint32_t laneBits(const core::LaneMask (&m)[W]) {
  std::uint32_t bits = 0;
  for (int l = 0; l < W; ++l)
    bits |= static_cast<std::uint32_t>(m[l] != 0) << l;
  return bits;
}

/// majorValue of large_deflection.cpp: the larger eigenvalue of [a c; c b]
LAMINA_CLONE_INLINE double majorValue(double a, double b, double c) {
  const double h = 0.5 * (a - b);
  return 0.5 * (a + b) + std::sqrt(h * h + c * c);
}

} // namespace

// f_a = h A0 F S dN_a in the element loop's order.
LAMINA_VECTOR_CLONES
std::uint32_t linearFabricForces(const LinearLaneLaw& law, const FabricLaneGroup& g,
                                 const double* x, double (&f)[9][kFabricLanes]) {
  core::LaneMask taut[W];
  LAMINA_LANES
  for (int l = 0; l < W; ++l) {
    double F0[3], F1[3], C[3], S[3];
    taut[l] = laneStress(law, g, x, l, F0, F1, C, S);
    const double hA = g.hA[l];
    for (int c = 0; c < 3; ++c) {
      const double P0 = hA * (F0[c] * S[0] + F1[c] * S[2]);
      const double P1 = hA * (F0[c] * S[2] + F1[c] * S[1]);
      f[c][l] = P0 * g.dN[0][l] + P1 * g.dN[1][l];
      f[3 + c][l] = P0 * g.dN[2][l] + P1 * g.dN[3][l];
      f[6 + c][l] = P0 * g.dN[4][l] + P1 * g.dN[5][l];
    }
  }
  return laneBits(taut);
}

// The fastest wave's speed as LargeDeflection::linearStableStep takes it.
LAMINA_VECTOR_CLONES
std::uint32_t linearFabricStableSteps(const LinearLaneLaw& law, const LaneWave& wave,
                                      const FabricLaneGroup& g, const double* x,
                                      const double* length, double (&dt)[kFabricLanes]) {
  core::LaneMask taut[W];
  LAMINA_LANES
  for (int l = 0; l < W; ++l) {
    double F0[3], F1[3], C[3], S[3];
    taut[l] = laneStress(law, g, x, l, F0, F1, C, S);
    const double stretch = std::max(majorValue(C[0], C[1], C[2]), 1.0);
    const double tension = std::max(majorValue(S[0], S[1], S[2]), 0.0);
    const double now = std::sqrt((stretch * wave.modulus + tension) / wave.density);
    dt[l] = length[l] / (now > wave.rest * (1 + 1e-12) ? now : wave.rest);
  }
  return laneBits(taut);
}

} // namespace lamina::membrane
