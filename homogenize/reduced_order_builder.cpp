#include "homogenize/reduced_order_builder.hpp"

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/resources.hpp"
#include "homogenize/cell_operator.hpp"
#include "homogenize/cg_solver.hpp"
#include "homogenize/cluster_interaction.hpp"
#include "homogenize/fft.hpp"
#include "homogenize/field_operator.hpp"
#include "homogenize/green_operator.hpp"
#include "homogenize/start_residual.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>

namespace lamina::homogenize {

namespace {

constexpr std::size_t kF = static_cast<std::size_t>(kConcentrationFeatures);

std::vector<std::string> namesOf(const std::vector<materials::ReducedOrderPhase>& phases) {
  std::vector<std::string> names;
  for (const auto& p : phases)
    names.push_back(p.name);
  return names;
}

std::vector<double> densitiesOf(const std::vector<materials::ReducedOrderPhase>& phases) {
  std::vector<double> rho;
  for (const auto& p : phases)
    rho.push_back(p.density);
  return rho;
}

/// @return the macro strain e_k scaled by @p s (lamina order)
std::array<double, 6> unit(int k, double s) {
  std::array<double, 6> E{0, 0, 0, 0, 0, 0};
  E[static_cast<std::size_t>(k)] = s;
  return E;
}

} // namespace

ReducedOrderBuilder::ReducedOrderBuilder(const Grid& grid, std::vector<std::int32_t> phase,
                                         std::vector<materials::ReducedOrderPhase> phases,
                                         bool micro_inertia, ReducedOrderOptions options)
    : grid_(grid), phase_(std::move(phase)), phases_(std::move(phases)),
      micro_inertia_(micro_inertia), opt_(std::move(options)), threads_(opt_.threads, grid.size()) {
  LAMINA_CHECK(phase_.size() == grid_.size(), "phase map has ", phase_.size(), " voxels, the grid ",
               grid_.size());
  LAMINA_CHECK(opt_.tol > 0, "tolerance must be positive");
  for (const auto& p : phases_)
    L0_.push_back(p.law.make()->elasticStiffness(1.0));
}

double ReducedOrderBuilder::memoryBytes(std::size_t voxels, int partitions, bool micro_inertia) {
  const double N = static_cast<double>(voxels), n = partitions;
  // concentration tensors 36, strain 6, S 3, CG vectors 9, FFT buffer ~6,
  // maps; with micro-inertia the six h spectra (~18) and 6 n influence
  // spectra (~3 each)
  const double per_voxel = 36 + 6 + 3 + 9 + 6 + 1 + (micro_inertia ? 18 + 18 * n : 0);
  // and per pair of partitions: P^(beta alpha) (36) and R (36, kept even
  // without micro-inertia)
  return 8 * (per_voxel * N + 72 * n * n);
}

ReducedOrderResult ReducedOrderBuilder::run() {
  const auto t0 = std::chrono::steady_clock::now();
  ReducedOrderResult res;
  // before any solve: K against the phases' voxels
  checkPartitionOptions(phase_, namesOf(phases_), opt_.partitions);
  const auto guard = threads_.guard();
  // 1. the six macro load cases: H_k, the concentration tensors, D_lin
  macroLoadCases(res);
  // 2. partitions, fractions and A^(alpha) (partition means)
  res.partitions = makePartitions(phase_, namesOf(phases_), features_.data(), opt_.partitions);
  concentrations(res);
  features_ = std::vector<double>(); // no longer needed
  // 3. per partition and unit eigenstrain: S, P, and R, Q (eq. 40)
  influenceFunctions(res);
  // 4. clustering: the interaction tensors
  if (opt_.scheme == materials::ReducedOrderScheme::Clustering) {
    ClusterInteraction g =
        clusterInteraction(grid_, res.partitions.label, res.partitions.voxels, threads_.count());
    res.model.scheme = opt_.scheme;
    res.model.Ga = std::move(g.Ga);
    res.model.Gb = std::move(g.Gb);
  }
  // 5. C, density, D_lin; the cost
  finish(res);
  res.cost.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.cost.peak_bytes = core::peakResidentBytes();
  return res;
}

void ReducedOrderBuilder::macroLoadCases(ReducedOrderResult& res) {
  Options o;
  o.tol = opt_.tol;
  o.max_iterations = opt_.max_iterations;
  o.threads = threads_.count();
  o.measure = opt_.measure;
  o.quiet = opt_.quiet;
  o.estimate = Estimate::Stress; // C comes from the partition means
  o.precision = Precision::Double;
  const std::size_t N = grid_.size();
  Homogenizer h(grid_, phase_, L0_, densitiesOf(phases_), o);
  const FieldOperator D(grid_);
  features_.assign(kF * N, 0.0);
  std::vector<double> eps(6 * N);
  if (micro_inertia_)
    acc_.emplace(grid_, phase_, densitiesOf(phases_));
  h.setDisplacementSink([&](int k, const double* u) {
    D.strain(u, unit(k, 1.0), eps.data());
    const long voxels = static_cast<long>(N);
    double* f = features_.data();
#pragma omp parallel for schedule(static)
    for (long v = 0; v < voxels; ++v)
      for (std::size_t i = 0; i < 6; ++i)
        f[kF * static_cast<std::size_t>(v) + 6 * static_cast<std::size_t>(k) + i] =
            eps[i * N + static_cast<std::size_t>(v)];
    if (acc_)
      acc_->addLoadCase(k, u);
  });
  res.linear = h.run();
  res.cost.solves += 6;
  for (const LoadCaseResult& c : res.linear.cases) {
    res.cost.iterations += c.iterations;
    res.cost.max_residual = std::max(res.cost.max_residual, c.residual);
  }
}

void ReducedOrderBuilder::concentrations(ReducedOrderResult& res) const {
  const Partitions& parts = res.partitions;
  materials::ReducedOrderModel& m = res.model;
  const std::size_t n = static_cast<std::size_t>(parts.count());
  m.phases = phases_;
  m.partition_phase = parts.phase;
  for (std::size_t a = 0; a < n; ++a)
    m.fraction.push_back(static_cast<double>(parts.voxels[a]) / static_cast<double>(grid_.size()));
  // A^(beta)(i, k) = mean over beta of feature 6 k + i (sums in voxel order)
  m.A.assign(n, materials::Matrix6::Zero());
  for (std::size_t v = 0; v < phase_.size(); ++v) {
    materials::Matrix6& A = m.A[static_cast<std::size_t>(parts.label[v])];
    const double* f = &features_[kF * v];
    for (int k = 0; k < 6; ++k)
      for (int i = 0; i < 6; ++i)
        A(i, k) += f[6 * k + i];
  }
  for (std::size_t a = 0; a < n; ++a)
    m.A[a] /= static_cast<double>(parts.voxels[a]);
}

void ReducedOrderBuilder::partitionMeans(const Partitions& parts, const double* eps, int col,
                                         std::vector<materials::Matrix6>& out, std::size_t stride,
                                         std::size_t offset) const {
  const std::size_t N = grid_.size(), n = static_cast<std::size_t>(parts.count());
  std::vector<double> sum(6 * n, 0.0);
  for (std::size_t v = 0; v < N; ++v) {
    double* s = &sum[6 * static_cast<std::size_t>(parts.label[v])];
    for (std::size_t i = 0; i < 6; ++i)
      s[i] += eps[i * N + v];
  }
  for (std::size_t b = 0; b < n; ++b)
    for (std::size_t i = 0; i < 6; ++i)
      out[b * stride + offset](static_cast<Eigen::Index>(i), col) =
          sum[6 * b + i] / static_cast<double>(parts.voxels[b]);
}

void ReducedOrderBuilder::influenceFunctions(ReducedOrderResult& res) {
  const Partitions& parts = res.partitions;
  materials::ReducedOrderModel& m = res.model;
  const std::size_t N = grid_.size(), n = static_cast<std::size_t>(parts.count());
  const Eigen::Index n6 = static_cast<Eigen::Index>(6 * n);
  m.P.assign(n * n, materials::Matrix6::Zero());
  m.R = Eigen::MatrixXd::Zero(n6, n6);
  m.Q = Eigen::MatrixXd::Zero(6, n6);
  // the six cases' reference medium and operator, in double precision
  const Distribution dist = Distribution::serial(grid_);
  const bool measure = opt_.measure > 0 || (opt_.measure < 0 && N > (1u << 18));
  VectorFft fft(grid_, dist, threads_.count(), measure, Precision::Double);
  const CellOperator A(grid_, phase_, L0_, dist);
  const GreenOperator M(grid_, res.linear.lambda0, res.linear.mu0, fft, dist);
  const materials::Matrix6 C0 =
      materials::Stiffness::fromLame(res.linear.lambda0, res.linear.mu0).matrix();
  CgSolver<double> cg(N, A, M, dist, static_cast<double>(N));
  Options o;
  o.tol = opt_.tol;
  o.max_iterations = opt_.max_iterations;
  const FieldOperator D(grid_);
  AlignedBuffer S(3 * N);
  std::vector<double> eps(6 * N);
  std::vector<std::int32_t> indicator(N);
  std::vector<materials::Stiffness> C_alpha(2); // {0, L0 of alpha's phase}
  core::ProgressLine progress("influence functions", static_cast<long>(6 * n), opt_.quiet);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t v = 0; v < N; ++v)
      indicator[v] = parts.label[v] == static_cast<std::int32_t>(a) ? 1 : 0;
    C_alpha[1] = L0_[static_cast<std::size_t>(parts.phase[a])];
    const StartResidual b(grid_, indicator, C_alpha, dist);
    for (int J = 0; J < 6; ++J) {
      const std::size_t col = 6 * a + static_cast<std::size_t>(J);
      LoadCaseResult r;
      try { // b = -D^T C' (-e_J) = D^T L0 e_J N^(alpha)
        r = cg.solve(b, unit(J, -1.0), C0(J, J), o.tol, o.max_iterations, {}, nullptr, S.data());
      } catch (const DivergenceError& e) {
        throw DivergenceError("partition " + std::to_string(a) + ", eigenstrain " +
                              std::to_string(J + 1) + ": " + e.message());
      } catch (const Interrupted&) {
        throw; // a stop, not an error of this solve: keeps its type
      } catch (const Error& e) {
        throw Error("partition " + std::to_string(a) + ", eigenstrain " + std::to_string(J + 1) +
                    ": " + e.message());
      }
      ++res.cost.solves;
      res.cost.iterations += r.iterations;
      res.cost.max_residual = std::max(res.cost.max_residual, r.residual);
      D.strain(S.data(), unit(0, 0.0), eps.data());
      partitionMeans(parts, eps.data(), J, m.P, n, a);
      if (acc_) { // eq. 40: Q column col, R row col up to the diagonal
        const InfluenceAverages av = acc_->addInfluence(S.data());
        const Eigen::Index c = static_cast<Eigen::Index>(col);
        for (int I = 0; I < 6; ++I)
          m.Q(I, c) = av.with_h[static_cast<std::size_t>(I)];
        for (std::size_t k = 0; k < av.with_s.size(); ++k)
          m.R(c, static_cast<Eigen::Index>(k)) = m.R(static_cast<Eigen::Index>(k), c) =
              av.with_s[k];
      }
      std::ostringstream os;
      os << "partition " << a + 1 << "/" << n << ", eigenstrain " << J + 1 << ": " << r.iterations
         << " iterations";
      progress.update(static_cast<long>(col + 1), os.str());
    }
  }
  progress.finish();
}

void ReducedOrderBuilder::finish(ReducedOrderResult& res) const {
  materials::ReducedOrderModel& m = res.model;
  m.C = m.referenceStiffness(L0_);
  const std::vector<std::size_t> count = voxelsPerPhase(phase_, phases_.size());
  m.density = 0;
  for (std::size_t p = 0; p < phases_.size(); ++p)
    m.density +=
        static_cast<double>(count[p]) / static_cast<double>(grid_.size()) * phases_[p].density;
  if (acc_) {
    res.dispersion = acc_->result();
    m.D_lin = res.dispersion->D;
  }
  res.cost.influence_doubles =
      acc_ ? static_cast<double>(acc_->influences() * acc_->doublesPerInfluence()) : 0.0;
  m.validate("reduced-order cell");
}

} // namespace lamina::homogenize
