#pragma once
/// @file homogenizer.hpp
/// @brief Effective stiffness of a periodic voxel cell: six load cases of the
/// cell problem solved by FFT-preconditioned conjugate gradients.
///
/// Method (docs/homogenize-solver.md): for each unit macroscopic strain E_k (lamina
/// order, engineering shear) find the periodic nodal displacement u with
/// D^T C (E_k + D u) = 0 (cell_operator.hpp), by conjugate gradients
/// preconditioned with the reference-medium Green operator
/// (green_operator.hpp). Column k of C is the average stress <C (E_k + D u)>.
/// The iteration count grows like sqrt(contrast): the preconditioned operator
/// has spectrum in [min, max] of the phase/reference modulus ratios.
///
/// Convergence criterion: sqrt(r^T K0^-1 r / (N E_k^T C0 E_k)) <= tol, i.e.
/// the error of the strain field in the reference energy norm relative to the
/// applied strain.
///
/// C from the six solutions (Estimate): by default the energy (Hill-Mandel)
/// form C_jk = <eps_j : C : eps_k>, whose error is e_j^T A e_k / N, quadratic
/// in the displacement errors e (the average stress <sigma_k>_j is off by
/// u_j^T A e_k / N, linear). It is evaluated without another pass over the
/// grid as C_jk = <sigma_k>_j - x_j^T r_k / N with the final residual r_k =
/// b_k - A x_k of case k, which needs the displacement x_j of the earlier
/// cases (six fields kept).

#include "core/parallel.hpp"
#include "homogenize/conjugate_gradients.hpp"
#include "homogenize/distribution.hpp"
#include "homogenize/fft.hpp"
#include "homogenize/grid.hpp"
#include "materials/stiffness.hpp"
#include "materials/symmetry.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lamina::homogenize {

class CellOperator;
class GreenOperator;
class StartResidual;

/// How C is formed from the six load cases.
enum class Estimate {
  Energy, ///< C_jk = <eps_j : C : eps_k>: error quadratic in the solver's (keeps 6 fields)
  Stress  ///< column k = <sigma_k>: error linear in the solver's, no extra memory
};

/// Solver settings.
struct Options {
  double tol = 1e-5;          ///< relative residual of each load case
  int max_iterations = 10000; ///< per load case; exceeding it is an error
  int threads = 0;            ///< OpenMP and FFTW threads (0: auto, 1 below 64k voxels)
  int measure = -1;           ///< FFTW_MEASURE planning: 1 yes, 0 no, -1 auto (above 64^3 voxels)
  bool quiet = true;          ///< no progress line
  Estimate estimate = Estimate::Energy; ///< how C is formed
  /// Precision of the preconditioner's FFTs (and, from tol
  /// kFloatVectorsTol up, of the cell operator and the CG vectors: see
  /// floatVectors(); sums over the grid and the CG scalars stay double);
  /// unset: single when tol >= 1e-6 (autoPrecision), else double
  std::optional<Precision> precision;
};

/// The precision Options::precision leaves unset means for @p tol: single
/// precision down to tol 1e-6 (its rounding, ~1e-7 relative, stays two
/// decades below the residual CG has to reach).
Precision autoPrecision(double tol);

/// The tolerance from which single-precision runs also keep the cell
/// operator and the CG vectors (r, p, A p, the displacements) in float.
/// Float vectors leave about 1e-8 of max|C| of rounding in C (7.8e-9
/// measured between ranks on the 128^3 sphere); the energy estimate's error
/// from the tolerance is quadratic in it (1.3e-6 of max|C| at 1e-3 on that
/// cell, so about 1e-8 at 1e-4). From 1e-4 up the rounding is thus at most
/// of the order of what the tolerance leaves; below, the vectors stay
/// double and C keeps the digits its tolerance buys (6e-11 of max|C| at
/// the default 1e-5), with only the preconditioner's transforms in float.
inline constexpr double kFloatVectorsTol = 1e-4;

/// @return true when the cell operator and the CG vectors run in float:
/// transforms in single precision (@p fft) and @p tol >= kFloatVectorsTol
bool floatVectors(Precision fft, double tol);

/// The OpenMP team of a cell solver: @p requested if positive, else (auto)
/// one thread below 65536 voxels (a CG iteration is then too short to
/// amortise the fork/join of its parallel loops, and on shared cores a team
/// can wait a scheduler slice per barrier) and all of them above.
int solverThreads(int requested, std::size_t voxels);

/// The thread guard of a cell solver: its team size, picked once by
/// solverThreads() (plans and buffers are made for it), and the scope that
/// sets it for OpenMP around each call into the solver.
class SolverThreads {
public:
  /// @param requested threads asked for (0: auto); @param voxels of the grid
  SolverThreads(int requested, std::size_t voxels)
      : count_(solverThreads(requested, voxels)) {}
  /// @return the team size
  int count() const { return count_; }
  /// @return a scope in which OpenMP runs count() threads (the caller's team
  /// size comes back when it ends)
  core::ThreadsScope guard() const { return core::ThreadsScope(count_); }

private:
  int count_;
};

/// Outcome of one load case: CG iterations and final relative residual.
using LoadCaseResult = CgResult;

/// Everything a homogenization produces.
struct Result {
  materials::Stiffness C_raw; ///< average stresses of the six load cases (columns)
  /// Effective C (Pa, lamina order): the energy form (Estimate::Energy,
  /// symmetric by construction) or the symmetrized C_raw (Estimate::Stress)
  materials::Stiffness C;
  double asymmetry = 0; ///< max |C_raw - C_raw^T| / max |C_raw| (a solver error gauge)
  double density = 0;   ///< volume average (kg/m^3)
  std::array<LoadCaseResult, 6> cases;                                   ///< per load case
  materials::Symmetry symmetry{materials::SymmetryClass::Triclinic, -1}; ///< class of C
  double symmetry_tol = 0;                 ///< relative tolerance used to classify
  double lambda0 = 0, mu0 = 0;             ///< reference medium (Pa)
  std::size_t voxels = 0;                  ///< number of voxels
  std::vector<double> voxel_fraction;      ///< per phase
  double wall_s = 0;                       ///< wall time of run() (s)
  Estimate estimate = Estimate::Energy;    ///< how C was formed
  Precision precision = Precision::Double; ///< FFT precision used
  bool float_vectors = false; ///< cell operator and CG vectors in float (floatVectors())
  /// @return the largest final residual of the six cases
  double maxResidual() const;
  /// @return the iterations of the six cases
  std::array<int, 6> iterations() const;
};

/// Reference Lame constants for the preconditioner: bulk and shear moduli
/// at the geometric means of the extreme phase moduli (Voigt/Reuss averages
/// for anisotropic phases), which balances the spectrum of K0^-1 A.
/// @param C stiffness of the phases that occur in the cell
void referenceMedium(const std::vector<materials::Stiffness>& C, double& lambda0, double& mu0);

/// The homogenization problem; run() reads as the method.
class Homogenizer {
public:
  /// @param grid voxel grid (n and voxel lengths)
  /// @param phase phase index per voxel (C order, x slowest)
  /// @param C stiffness per phase (lamina order, Pa; validated here)
  /// @param density density per phase (kg/m^3)
  /// @param options solver settings
  Homogenizer(const Grid& grid, std::vector<std::int32_t> phase,
              std::vector<materials::Stiffness> C, std::vector<double> density, Options options);
  /// Distributed: @p phase is this rank's slab of @p dist (every rank calls
  /// run(); all get the same Result).
  Homogenizer(const Grid& grid, const Distribution& dist, std::vector<std::int32_t> phase,
              std::vector<materials::Stiffness> C, std::vector<double> density, Options options);

  /// Called after each CG iteration: load case (0-5), iteration, residual.
  using Monitor = std::function<void(int, int, double)>;
  /// Installs @p m (replaces the built-in progress line).
  void setMonitor(Monitor m) { monitor_ = std::move(m); }

  /// Called after each load case k (0-5) with its converged nodal
  /// displacement fluctuation u (3 x N, component-major, the units of the
  /// grid spacing per unit strain; distributed: this rank's slab, 3 x
  /// dist.localSize()). The energy estimate forms u anyway; with the stress
  /// estimate a sink costs one more vector and update per iteration.
  using DisplacementSink = std::function<void(int, const double*)>;
  /// Installs @p s (see DisplacementSink).
  void setDisplacementSink(DisplacementSink s) { sink_ = std::move(s); }

  /// Solves the six load cases and returns C, density and diagnostics.
  /// Throws lamina::DivergenceError on NaN/Inf, lamina::Error when a case
  /// does not converge within max_iterations.
  Result run();

private:
  /// The six load cases with CG vectors of type V (float or double), the
  /// operator A, the start residuals b and the preconditioner M: fills
  /// res.cases and the columns of C (average stresses) and C_energy.
  template <class V>
  void solveCases(const CellOperator& A, const StartResidual& b, const GreenOperator& M,
                  const materials::Stiffness& C0, Result& res, materials::Matrix6& C,
                  materials::Matrix6& C_energy);

  Grid grid_;
  Distribution dist_;
  std::vector<std::int32_t> phase_;
  std::vector<materials::Stiffness> C_;
  std::vector<double> density_;
  Options opt_;
  Monitor monitor_;
  DisplacementSink sink_;
};

} // namespace lamina::homogenize
