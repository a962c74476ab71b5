#pragma once
/// @file law_lanes.hpp
/// @brief stepLawPoint (law_point.hpp) for kLawLanes elements of one GVBO
/// section at once: the step of a rate-dependent sheet, vectorized across
/// elements.
///
/// Every part of the one-element step is taken per lane in lockstep loops
/// that the compiler vectorizes (LAMINA_VECTOR_CLONES, core/vector_clones.hpp):
/// the completed deformation gradients, the midpoint (Hughes-Winget)
/// increment with the polar rotation of the midpoint gradient (Newton's
/// iteration, each lane stopping at its own converged iterate), the law's
/// plane-stress step (materials/gvbo_lanes.hpp), the energy terms, the new
/// history, the second Piola-Kirchhoff stress and the nodal forces. Each
/// lane follows the one-element step's formulas and iterates, so the two
/// agree to round-off (tests/membrane/law_lanes_test.cpp); near a threshold
/// (a convergence test, a tension-only element whose minor stress is about
/// zero) the round-off can tip a lane to the neighbouring iterate or branch.
///
/// Lanes that meet a case the lanes do not take are handed back (their bit
/// is clear in the returned mask) and the caller steps them with
/// stepLawPoint, which has the safeguards and the error messages: a
/// degenerate element, a polar iteration that needs the SVD, the law's
/// step declined or not converged, and, in a tension-only section, a
/// compressive principal stress (the wrinkled and slack solves).

#include "materials/gvbo_law.hpp"

namespace lamina::membrane {

/// Elements per call (materials::kGvboLanes).
inline constexpr int kLawLanes = 8;

/// The elements' inputs and outputs, one column per lane.
struct LawLaneStep {
  /// F at t_{n+1}, 3 x 2 column-major (F[r + 3 c][lane])
  double F[6][kLawLanes];
  const double* block_n[kLawLanes]; ///< history at t_n (LawPoint layout)
  double* block[kLawLanes];         ///< history at t_{n+1}, written for the lanes taken
  /// dN_a of the element in its reference frame: x0, y0, x1, y1, x2, y2 (1/m)
  double dN[6][kLawLanes];
  double hA[kLawLanes];   ///< reference thickness x area (m^3)
  double S[3][kLawLanes]; ///< out: [S11, S22, S12] (Pa), lanes taken
  /// out: the nodal forces h0 A0 F S dN_a, node a's x, y, z at 3 a + c (N), lanes taken
  double f[9][kLawLanes];
};

/// Steps every lane of @p io with GVBO law @p law over @p dt, as
/// stepLawPoint(law, F, tension_only, dt, block_n, block) would, and the
/// nodal forces of its stress.
/// @return the mask of the lanes taken (bit l for lane l); the caller steps
/// the others with stepLawPoint (whose block they may have written)
unsigned stepGvboLawPoints(const materials::GvboLaw& law, bool tension_only, double dt,
                           LawLaneStep& io);

} // namespace lamina::membrane
