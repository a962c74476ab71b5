#pragma once
/// @file reduced_order_builder.hpp
/// @brief Computes the reduced-order model of a voxel cell
/// (materials/reduced_order.hpp; polyurea chapter section 4.2, eqs. 22-34,
/// micro-inertia eqs. 37-40) once, by periodic FFT-preconditioned solves on
/// its plain phase map: what `homogenize --reduced-order` writes into the
/// library and the reduced-order law evaluates at every material point.
///
/// Method (run(); docs/homogenize-nonlinear.md, "Reduced-order cells"):
/// 1. Every phase's reference stiffness L0 = its law's elasticStiffness(1.0).
///    The six macro load cases of the linear solver (Homogenizer, stress
///    estimate, double precision) give the displacements H_k; their voxel
///    strains e_k + D H_k are each voxel's strain concentration tensor (6x6,
///    column k under unit macro strain k), and, for a cell with a size in
///    metres, H_k goes to the dispersion accumulator (D_lin, eqs. 38-39).
/// 2. Partitions (partition.hpp): one per phase, or k-means per phase on
///    the strain concentration tensors. A^(alpha) is the mean concentration
///    tensor of partition alpha, c_alpha its voxel fraction.
/// 3. For every partition alpha and unit eigenstrain J (engineering, lamina
///    order), one periodic solve of div L0 (grad S - e_J N^(alpha)) = 0 at
///    zero macro strain: A S = D^T L0 e_J N^(alpha), whose right-hand side
///    is the load case's -D^T C' E with E = -e_J and the stiffness list C' =
///    {0, L0 of alpha's phase} on the indicator map of alpha
///    (start_residual.hpp), solved by the same conjugate-gradient loop
///    (cg_solver.hpp) with the six cases' reference medium. Column J of
///    P^(beta alpha) is the mean strain D S of partition beta. With a cell
///    size: R and Q of eq. 40 from S's spectrum (DispersionAccumulator::
///    addInfluence), in kg/m.
/// 4. Clustering (options.scheme): the interaction tensors
///    Ga, Gb of the partitions (cluster_interaction.hpp), no further solve.
/// 5. C = sym(sum_beta c_beta L0_beta A^(beta)) (the stress estimate of the
///    six cases, symmetrized: the stiffness the reduced-order law has when
///    every phase stays elastic), rho_c the voxel-weighted density.
///
/// Exact identities of any cell (the tests use them): sum c_b A^(b) = I,
/// sum_b c_b P^(b a) = 0 (a periodic strain has zero mean); sum_a P^(b a) =
/// I - A^(b) and sum_a S^(a) = -H (a unit eigenstrain everywhere is the
/// negative of a unit macro strain), both to the solver tolerance.
///
/// Cost: 6 + 6 n solves for n partitions. Memory (doubles, N voxels,
/// Nc = n0 n1 (n2/2 + 1) Fourier modes): the strain concentration tensors,
/// 36 N, kept from the six cases to the partition means; the CG vectors
/// and the strain of one solve, about 18 N; with a cell size the spectra of
/// the six h, 36 Nc, and of every influence function, 6 Nc each: 36 n Nc
/// (about 18 n N) for R, which pairs every S^(alpha)_J with every other.
/// memoryBytes() estimates the total.
///
/// Scope: serial (one process, OpenMP threads; no MPI). Composite voxels do
/// not enter (the plain map, as the nonlinear path uses): a voxel is its
/// centre's phase. The solves run in double precision.

#include "homogenize/dispersion.hpp"
#include "homogenize/grid.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/partition.hpp"
#include "materials/reduced_order.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace lamina::homogenize {

/// Settings of a reduced-order build.
struct ReducedOrderOptions {
  /// CG tolerance of every solve (cg_solver.hpp); the identities above hold
  /// to about this, C's symmetry too
  double tol = 1e-8;
  int max_iterations = 10000;  ///< per solve; exceeding it is an error
  int threads = 0;             ///< OpenMP and FFTW threads (0: solverThreads())
  int measure = -1;            ///< FFTW_MEASURE: 1 yes, 0 no, -1 auto (above 64^3)
  bool quiet = true;           ///< no progress line
  PartitionOptions partitions; ///< how the cell is split
  /// how the law couples the partitions; clustering adds
  /// the interaction tensors Ga, Gb (cluster_interaction.hpp) to the model
  materials::ReducedOrderScheme scheme = materials::ReducedOrderScheme::Transformation;
};

/// The one-off cost of a build.
struct ReducedOrderCost {
  int solves = 0;          ///< 6 macro load cases + 6 per partition
  long iterations = 0;     ///< CG iterations of all solves
  double max_residual = 0; ///< largest final residual of a solve
  double wall_s = 0;       ///< wall time of run() (s)
  double peak_bytes = 0;   ///< peak resident set of the process at the end (bytes)
  /// doubles held for R and Q: the spectra of the 6 n influence functions
  /// (6 Nc each; 0 without micro-inertia)
  double influence_doubles = 0;
};

/// Everything a build produces.
struct ReducedOrderResult {
  materials::ReducedOrderModel model;   ///< the model (validated)
  Partitions partitions;                ///< which voxels form each partition
  Result linear;                        ///< the six macro load cases (Homogenizer)
  std::optional<Dispersion> dispersion; ///< D_lin and diagnostics (cells with a size)
  ReducedOrderCost cost;                ///< solves, iterations, time, memory
};

/// The reduced-order build of one cell; run() reads as the method.
class ReducedOrderBuilder {
public:
  /// @param grid voxel grid (lengths in metres for R, Q and D_lin in kg/m)
  /// @param phase phase index per voxel (C order), into @p phases
  /// @param phases the cell's phases (name, law, density); each law's
  ///   elasticStiffness(1.0) is its L0
  /// @param micro_inertia compute D_lin, R and Q (the grid is in metres);
  ///   without, they are zero
  /// @param options tolerances, threads, partitions
  ReducedOrderBuilder(const Grid& grid, std::vector<std::int32_t> phase,
                      std::vector<materials::ReducedOrderPhase> phases, bool micro_inertia,
                      ReducedOrderOptions options);

  /// Runs the method. Throws lamina::Error for bad partition options
  /// (before any solve) or a solve that does not converge,
  /// lamina::DivergenceError on NaN/Inf.
  ReducedOrderResult run();

  /// @return an estimate of the memory (bytes) of a build of @p voxels
  /// voxels into @p partitions partitions (see the file comment)
  static double memoryBytes(std::size_t voxels, int partitions, bool micro_inertia);

private:
  void macroLoadCases(ReducedOrderResult& res);
  void concentrations(ReducedOrderResult& res) const;
  void influenceFunctions(ReducedOrderResult& res);
  /// partition means of a strain field (6 x N): column @p col of out[beta]
  void partitionMeans(const Partitions& parts, const double* eps, int col,
                      std::vector<materials::Matrix6>& out, std::size_t stride,
                      std::size_t offset) const;
  void finish(ReducedOrderResult& res) const;

  Grid grid_;
  std::vector<std::int32_t> phase_;
  std::vector<materials::ReducedOrderPhase> phases_;
  std::vector<materials::Stiffness> L0_; // per phase
  bool micro_inertia_;
  ReducedOrderOptions opt_;
  SolverThreads threads_;
  std::vector<double> features_; // 36 per voxel (partition.hpp)
  std::optional<DispersionAccumulator> acc_;
};

} // namespace lamina::homogenize
