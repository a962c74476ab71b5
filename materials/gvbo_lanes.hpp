#pragma once
/// @file gvbo_lanes.hpp
/// @brief The isotropic GVBO law's membrane plane-stress step
/// (GvboLaw::planeStressStep) for kGvboLanes material points at once.
///
/// The same Newton as GvboLaw::planeStressStep, on (deps_zz, Gamma) with the
/// moduli at the J of each iterate and the same two convergence tests, run
/// in lockstep over the lanes: every lane's arithmetic is an independent
/// loop over the lanes, so the compiler vectorizes across points (the widest
/// vectors the CPU has: LAMINA_VECTOR_CLONES, core/vector_clones.hpp), and a
/// lane stops updating at the iterate where its own tests hold. Each lane
/// takes the iterates and tests that the one-point step takes, so the
/// results agree with it to round-off (vector code may contract a * b + c
/// into one rounding, a divisor used twice is inverted once, exp and log are
/// glibc's vector variants, core/vector_math.hpp); near a test's threshold
/// that round-off can stop a lane one iterate apart from the one-point step,
/// a difference of the size of the convergence tolerance.
///
/// A lane is not taken (its bit is clear in the returned mask, and the
/// caller steps that point with the one-point path, which has the safeguards
/// and the error messages) when the one-point step would decline or fail:
/// transverse shear in the strain or the state, a J that is not positive, a
/// non-finite stress or residual, a Newton step that turns Gamma negative,
/// or no convergence within kPlaneStressMaxIterations.
///
/// Used by the large-deflection membrane for the elements of a GVBO section
/// (membrane/model/law_lanes.hpp), where the step is the cost of the run.

#include "materials/gvbo.hpp"

namespace lamina::materials {

/// Points per call (one AVX-512 vector, two AVX2 ones).
inline constexpr int kGvboLanes = 8;

/// In- and outputs of gvboPlaneStressLanes, one column per lane. Strains are
/// in the law's rotation-free frame, engineering shear; [4] holds xx, yy,
/// zz, xy (the transverse shears are zero on every lane taken).
struct GvboLanes {
  // inputs
  double eps_n[6][kGvboLanes];       ///< the law's strain at t_n, lamina order
  double deps_p[3][kGvboLanes];      ///< imposed in-plane increment [xx, yy, xy]
  double lambda3_n[kGvboLanes];      ///< thickness stretch at t_n
  double J2_n[kGvboLanes];           ///< in-plane area ratio of the law at t_n
  double J2[kGvboLanes];             ///< ... at t_{n+1}
  const double* state_n[kGvboLanes]; ///< GvboState at t_n
  double* state[kGvboLanes];         ///< GvboState at t_{n+1}, written for the lanes taken
  // outputs, lanes taken
  double deps_zz[kGvboLanes];  ///< the normal strain increment solved for
  double lambda3[kGvboLanes];  ///< thickness stretch at t_{n+1}
  double sigma[4][kGvboLanes]; ///< Cauchy stress xx, yy, zz (~0), xy (Pa)
  double K[kGvboLanes];        ///< bulk modulus at J_{n+1} (the last iterate's)
  double G[kGvboLanes];        ///< shear modulus at J_{n+1}
};

/// Takes GvboLaw::planeStressStep on every lane of @p io (no free
/// direction) over @p dt with convergence @p tolerance (plane_stress.hpp).
/// @return the mask of the lanes taken (bit l for lane l); the outputs and
/// the state at t_{n+1} of the others are unspecified
unsigned gvboPlaneStressLanes(const GvboParameters& p, double dt, double tolerance, GvboLanes& io);

} // namespace lamina::materials
