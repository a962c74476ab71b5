#pragma once
/// @file nonlinear_homogenizer.hpp
/// @brief The periodic cell with a constitutive law (materials::ConstitutiveLaw)
/// at every voxel under a macroscopic loading history: Newton's method with
/// the consistent tangent, each Newton system solved by conjugate gradients
/// preconditioned with the FFT Green operator of the linear solver.
///
/// Method (docs/homogenize-nonlinear.md, "Nonlinear homogenization"). Small strain.
/// Unknowns of step n+1: the periodic nodal displacement u and the
/// stress-controlled macroscopic strains E_f. They make stationary the
/// incremental potential sum_v w_v(E + D u) - N Sigma_f . E_f, whose
/// gradient is the residual
///     r_u = -D^T sigma(E + D u),   r_f = N Sigma_f - sum_v sigma_f,
/// and whose Hessian, with the per-voxel tangent C_t = d sigma / d eps
/// (symmetrized), is the symmetric block operator
///     [D^T C_t D, D^T C_t P; P^T C_t D, P^T C_t P]   (sums over voxels).
/// Each Newton step solves it by CG preconditioned with blockdiag(K0^+,
/// (N P^T C0 P)^-1) (the Green operator of the isotropic reference medium
/// C0 and its mean part), to a relative accuracy eta (inexact Newton).
/// A step starts from the previous fields extrapolated linearly in time.
/// Convergence: sqrt(r^T M r / (N e^T C0 e)) <= tol, M the preconditioner,
/// e the current macroscopic strain (floor 1e-6): the strain error in the
/// reference energy norm relative to the applied strain, as in the linear
/// solver.

#include "homogenize/grid.hpp"
#include "homogenize/macro_history.hpp"
#include "materials/law.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace lamina::homogenize {

/// Settings of the nonlinear solver.
struct NonlinearOptions {
  double tol = 1e-5;     ///< Newton: relative residual (strain error / applied strain)
  double eta = 0.1;      ///< CG: relative reduction of the Newton residual per step
  int max_newton = 50;   ///< per load step; exceeding it is an error
  int max_krylov = 5000; ///< per Newton step; exceeding it is an error
  int threads = 0;       ///< OpenMP and FFTW threads (0: auto as the linear solver)
  int measure = -1;      ///< FFTW_MEASURE: 1 yes, 0 no, -1 auto (above 64^3)
};

/// Outcome of one load step.
struct StepResult {
  int step = 0;                            ///< 1-based
  double t = 0;                            ///< s
  materials::Vector6 E;                    ///< macroscopic strain (lamina, engineering shear)
  materials::Vector6 Sigma;                ///< macroscopic stress (Pa)
  std::vector<materials::Vector6> phase_E; ///< per-phase average strain
  std::vector<materials::Vector6> phase_S; ///< per-phase average stress
  int newton = 0;                          ///< Newton iterations
  int krylov = 0;                          ///< CG iterations, all Newton steps
  double residual = 0;                     ///< final relative residual
  double wall_s = 0;                       ///< wall time of the step
};

/// Nonlinear cell problem. Holds the fields and the state of every voxel.
class NonlinearHomogenizer {
public:
  /// @param grid voxel grid; @param phase phase index per voxel; @param laws
  /// law per phase (linear laws keep no per-voxel data); @param options settings
  NonlinearHomogenizer(const Grid& grid, std::vector<std::int32_t> phase,
                       std::vector<materials::LawPtr> laws, NonlinearOptions options);
  ~NonlinearHomogenizer();
  NonlinearHomogenizer(const NonlinearHomogenizer&) = delete;
  NonlinearHomogenizer& operator=(const NonlinearHomogenizer&) = delete;

  /// Solves every step of @p history from the current state (t continues
  /// from the last step run); @p report is called after each step.
  /// Throws lamina::Error when Newton or CG does not converge.
  std::vector<StepResult> run(const MacroHistory& history,
                              const std::function<void(const StepResult&)>& report = {});

  /// Effective consistent tangent d Sigma / d E (6x6, lamina order, Pa) of a
  /// strain increment applied over @p dt from the current state: the
  /// per-voxel algorithmic tangents of that step (symmetrized) homogenized
  /// by six linear solves. dt = 0: instantaneous (infinite-rate) tangent.
  materials::Matrix6 effectiveTangent(double dt);

  /// @return the voxel strains of the last step (6 x N, component-major)
  const std::vector<double>& strainField() const;
  /// @return the voxel stresses of the last step (6 x N, component-major)
  const std::vector<double>& stressField() const;
  /// @return the grid
  const Grid& grid() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace lamina::homogenize
