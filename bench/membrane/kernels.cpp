// Times the building blocks of a membrane step on a benchmark mesh, each
// against one product with the linear model's K in plain 3x3 blocks (the
// memory floor of an assembled K, "floor" below) on the same mesh:
// - N: bench/membrane/bench.toml, the structured N x N squares (2 triangles
//   each, centre strike, tau = 0.4 h_el / c_S);
// - MESH (a .msh or .geo file): bench/membrane/bench-gmsh.toml on that mesh
//   (tau = 4.3e-6 s; run.sh makes the unstructured benchmark square).
// What is timed (best and median wall over the repetitions, mean CPU over
// all threads, per call):
// - one product with K in each storage: scalar CSR, plain 3x3 blocks (the
//   floor), and the solvers' own storage interleaved and planar (shared
//   stencil rows on uniform structured meshes; elsewhere split blocks when
//   no block couples u, v with w, as for an isotropic law, else the plain
//   blocks; "solver storage" below);
// - the Newmark step of the linear model (predictors, K u~, the CG solve,
//   correctors), with its CG iterations per step; printed against the floor
//   as the step itself and as step / (iterations + 1): the step costs one
//   product with K plus one with A per iteration, so this charges the step's
//   vector passes to the products (an upper bound of one CG iteration
//   inside the step);
// - one CG iteration: StepSolver::solve on A = M + tau^2 beta2 / 2 K (the
//   step's matrix without the identity rows of the constrained DOFs: the
//   same blocks, pattern and preconditioner) for b = A x_r (x_r random),
//   from x = 0 to the case's tolerance, divided by its iterations; the time
//   includes the solve's start (x zeroed, residual, planar copies), shared
//   over its iterations; on split blocks also for b without in-plane part
//   (a transverse load: the products compute the normal plane alone);
// - one explicit (central-difference) step of the large-deflection fabric
//   model and its internal force, and one explicit step of the linear model.
// Wall times are the best of the repetitions (the machine is shared: the
// best is the least disturbed), CPU times the mean over all threads.
// Usage: membrane_kernels N|MESH THREADS [STEPS] [all|explicit|law] [--json FILE]
//   explicit: only the floor and the explicit steps (large meshes)
//   law: the explicit step of bench/membrane/gvbo.toml (N x N polyurea
//        sheet) with a GVBO section against the same sheet elastic at the
//        GVBO rest moduli, and their ratio (bench/membrane/gvbo.sh)
//   --json FILE: also writes what was printed to FILE as one JSON object:
//        mesh, triangles, dofs, threads, steps, "timings" {key: {best_ms,
//        median_ms, cpu_ms}}, "ratios" {key: {best, cpu}}, and
//        cg_iterations_per_step, cg_solve_iterations (run.sh reads it)
#include "membrane/integrators/step_solver.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/model/block_matrix.hpp"
#include "membrane/simulation.hpp"
#include "timing.hpp"

#include <nlohmann/json.hpp>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

using namespace lamina;

namespace {

using bench::timeIt;
using bench::Timing;

/// What the run printed, by key, for --json FILE.
class Report {
public:
  /// Times @p fn as bench::timeIt (printing @p what) and records it under @p key.
  template <class F>
  Timing time(const char* key, const char* what, int reps, F&& fn) {
    const Timing t = timeIt(what, reps, std::forward<F>(fn));
    json_["timings"][key] = {
        {"best_ms", 1e3 * t.best}, {"median_ms", 1e3 * t.median}, {"cpu_ms", 1e3 * t.cpu}};
    return t;
  }
  /// Prints a / b for the best wall and the CPU times and records them under @p key.
  void ratio(const char* key, const char* what, Timing a, Timing b) {
    std::printf("  %-32s %.2f (best wall)  %.2f (cpu)\n", what, a.best / b.best, a.cpu / b.cpu);
    json_["ratios"][key] = {{"best", a.best / b.best}, {"cpu", a.cpu / b.cpu}};
  }
  /// @return the entry @p key of the JSON object
  nlohmann::json& operator[](const char* key) { return json_[key]; }
  /// Writes the object to @p file (nothing when empty); exits 1 if it cannot.
  void write(const std::string& file) const {
    if (file.empty())
      return;
    std::ofstream out(file);
    out << json_.dump() << "\n";
    if (!out) {
      std::fprintf(stderr, "membrane_kernels: cannot write %s\n", file.c_str());
      std::exit(1);
    }
  }

private:
  nlohmann::json json_ = nlohmann::json::object();
};

/// @return @p t divided by @p n (per iteration of a timed call)
Timing per(Timing t, double n) {
  return {t.best / n, t.cpu / n, t.median / n};
}

/// The explicit step of bench/membrane/gvbo.toml at N x N with the section of
/// catalog material @p material, whose law must be linear iff @p linear
/// (else it exits 1: a timing of the wrong path is worse than none); prints
/// the line and @return its timing.
Timing lawStep(Report& report, int N, int steps, const char* material, bool linear, const char* key,
               const char* what) {
  const std::vector<std::string> set{"mesh.nx=" + std::to_string(N),
                                     std::string("section[0].material=") + material};
  const membrane::Model model = membrane::readCase(LAMINA_SOURCE_DIR "/bench/membrane/gvbo.toml",
                                                   set, {"/nonexistent/library.toml", ""});
  if (model.sections.at(0).isLinear() != linear) {
    std::fprintf(stderr, "membrane_kernels: the section of '%s' is %s; expected %s\n", material,
                 linear ? "not linear" : "linear", linear ? "linear" : "its nonlinear law");
    std::exit(1);
  }
  membrane::Simulation sim(model);
  return report.time(key, what, steps, [&] { sim.step(); });
}

/// `law` mode: GVBO sheet against the elastic sheet, best wall and CPU per step.
void lawMode(Report& report, int N, int threads, int steps) {
  std::printf("N = %d (%d triangles), threads = %d, polyurea sheet (bench/membrane/gvbo.toml)\n", N,
              2 * N * N, threads);
  const Timing elastic = lawStep(report, N, steps, "polyurea-elastic-rest", true, "elastic_step",
                                 "explicit step, elastic");
  const Timing gvbo =
      lawStep(report, N, steps, "polyurea-gvbo", false, "gvbo_step", "explicit step, GVBO");
  report.ratio("gvbo_step/elastic_step", "GVBO step / elastic step", gvbo, elastic);
  std::printf("  per element and step: GVBO %.3f us wall, %.3f us cpu\n",
              1e6 * gvbo.best / (2.0 * N * N), 1e6 * gvbo.cpu / (2.0 * N * N));
}

/// The floor and the product in the solvers' storage (interleaved vectors).
struct Products {
  Timing floor, solver;
};

/// The products with K: the floor (plain 3x3 blocks), the solvers' storage
/// interleaved and, with @p all, scalar CSR and the solvers' storage planar.
/// @return the floor's and the solvers' storage's timings
Products products(Report& report, const membrane::SparseMatrix& K, bool all) {
  Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows()), y(K.rows());
  const int reps = 30;
  const membrane::BlockMatrix plain(K, membrane::BlockStorage::Plain);
  const Timing floor =
      report.time("floor", "SpMV K, 3x3 blocks (floor)", reps, [&] { plain.multiply(x, y); });
  const membrane::BlockMatrix shared(K);
  if (shared.sharedRows() > 0)
    std::printf("  (solver storage: shared stencil rows, %d stored rows)\n", shared.sharedRows());
  else
    std::printf("  (solver storage: %s)\n",
                shared.splitBlocks() ? "split blocks, 2x2 in-plane and normal" : "3x3 blocks");
  const Timing solver = report.time("spmv_solver", "SpMV K, solver storage, interleaved", reps,
                                    [&] { shared.multiply(x, y); });
  if (!all)
    return {floor, solver};
  report.time("spmv_csr", "SpMV K, scalar CSR", reps, [&] { membrane::multiply(K, x, y); });
  Eigen::VectorXd xs = x, ys = y;
  report.time("spmv_planar", "SpMV K, solver storage, planar", reps, [&] {
#pragma omp parallel
    {
      const int n = shared.nodes();
      const int t = omp_get_thread_num(), nt = omp_get_num_threads();
      shared.multiplyPlanar(xs.data(), ys.data(), n * t / nt, n * (t + 1) / nt);
    }
  });
  return {floor, solver};
}

/// @return true when the solver stores @p A in split blocks
bool solverSplit(const membrane::SparseMatrix& A) {
  const membrane::BlockMatrix B(A);
  return B.sharedRows() == 0 && B.splitBlocks();
}

/// One CG solve of A = M + tau^2 beta2 / 2 (1 + alpha) K of @p sim's Newmark
/// scheme (no constraint rows) for b = A x_r from x = 0 (file comment);
/// prints it per iteration against @p floor.
void cgIteration(Report& report, const membrane::Simulation& sim, Timing floor) {
  const auto& ts = sim.model().time;
  const double ck = 0.5 * ts.dt * ts.dt * ts.beta2 * (1 + ts.hht_alpha);
  const membrane::SparseMatrix A = sim.M() + ck * sim.K();
  membrane::StepSolver solver(A, membrane::LinearSolverKind::Cg, ts.tolerance, ts.max_iterations);
  const Eigen::VectorXd b = A * Eigen::VectorXd::Random(A.rows());
  Eigen::VectorXd x;
  int iterations = 0;
  const Timing solve = report.time("cg_solve", "CG solve, random b, from x = 0", 10, [&] {
    x.setZero(A.rows());
    iterations = solver.solve(b, x);
  });
  std::printf("  (CG iterations of that solve: %d)\n", iterations);
  report["cg_solve_iterations"] = iterations;
  report.ratio("cg_iteration/floor", "CG iteration / floor", per(solve, iterations), floor);
  if (!solverSplit(A))
    return;
  // The same with b's in-plane components zero (a transverse load): split
  // blocks, so the products compute the normal plane alone.
  Eigen::VectorXd bt = b;
  for (Eigen::Index i = 0; i < bt.size(); i += 3)
    bt[i] = bt[i + 1] = 0;
  int normal_iterations = 0;
  const Timing normal =
      report.time("cg_solve_normal", "CG solve, transverse b (normal plane alone)", 10, [&] {
        x.setZero(A.rows());
        normal_iterations = solver.solve(bt, x);
      });
  std::printf("  (CG iterations of that solve: %d)\n", normal_iterations);
  report.ratio("cg_iteration_normal/floor", "CG iteration, normal plane alone / floor",
               per(normal, normal_iterations), floor);
}

/// The Newmark step (CG) of @p model, against @p floor, then one CG iteration.
void newmark(Report& report, const membrane::Model& model, int steps, Timing floor) {
  membrane::Simulation sim(model);
  const membrane::SolverStats st0 = sim.integrator().stats();
  const Timing step = report.time("newmark_step", "Newmark step (CG)", steps, [&] { sim.step(); });
  const membrane::SolverStats st1 = sim.integrator().stats();
  const double its = double(st1.iterations - st0.iterations) / double(st1.solves - st0.solves);
  std::printf("  (CG iterations per step: %.1f)\n", its);
  report["cg_iterations_per_step"] = its;
  report.ratio("newmark_step/floor", "Newmark step / floor", step, floor);
  report.ratio("newmark_product/floor", "step / (CG its + 1) / floor", per(step, its + 1), floor);
  cgIteration(report, sim, floor);
}

/// The explicit steps (dt = safety x stable step; the strike keeps them
/// moving): the fabric's internal force and step and, with @p all, the
/// linear model's step, against the floor and the shared rows' product.
void explicitSteps(Report& report, const membrane::Model& model, int steps, Products spmv,
                   bool all) {
  const Timing floor = spmv.floor;
  membrane::Model fabric = model;
  fabric.kind = membrane::ModelKind::LargeDeflection;
  fabric.time.integrator = membrane::IntegratorKind::Explicit;
  fabric.time.dt = 0;
  {
    membrane::Simulation sim(fabric);
    Eigen::VectorXd f;
    const Timing force = report.time("fabric_force", "fabric internal force", 30,
                                     [&] { sim.structure().internalForce(sim.u(), f); });
    const Timing step =
        report.time("fabric_step", "explicit step, large deflection", steps, [&] { sim.step(); });
    report.ratio("fabric_step/floor", "large-deflection step / floor", step, floor);
    report.ratio("fabric_step/solver_spmv", "large-deflection step / solver SpMV", step,
                 spmv.solver);
    report.ratio("fabric_force/floor", "internal force / floor", force, floor);
  }
  if (all) {
    membrane::Model linear = fabric;
    linear.kind = membrane::ModelKind::Linear;
    linear.time.lumped = true;
    membrane::Simulation sim(linear);
    const Timing step =
        report.time("linear_step", "explicit step, linear", steps, [&] { sim.step(); });
    report.ratio("linear_step/floor", "linear step / floor", step, floor);
    report.ratio("linear_step/solver_spmv", "linear step / solver SpMV", step, spmv.solver);
  }
}

/// @return the benchmark case of @p mesh_arg (N, or a mesh file when @p mesh_file)
membrane::Model benchmarkCase(const std::string& mesh_arg, bool mesh_file) {
  const int N = mesh_file ? 0 : std::atoi(mesh_arg.c_str());
  const double c = std::sqrt(1e9 / (2 * 1.3) / 1000), dt = mesh_file ? 4.3e-6 : 0.4 / N / c;
  std::vector<std::string> set{"time.dt=" + std::to_string(dt),
                               "time.t_end=" + std::to_string(1000 * dt)};
  set.push_back(mesh_file ? "mesh.file=\"" + std::filesystem::absolute(mesh_arg).string() + "\""
                          : "mesh.nx=" + std::to_string(N));
  return membrane::readCase(mesh_file ? LAMINA_SOURCE_DIR "/bench/membrane/bench-gmsh.toml"
                                      : LAMINA_SOURCE_DIR "/bench/membrane/bench.toml",
                            set, {"/nonexistent/library.toml", ""});
}

/// @return whether @p arg names a mesh file (.msh or .geo) rather than N
bool isMeshFile(const std::string& arg) {
  const auto ends = [&](const char* s) {
    const std::string e(s);
    return arg.size() > e.size() && arg.compare(arg.size() - e.size(), e.size(), e) == 0;
  };
  return ends(".msh") || ends(".geo");
}

} // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args;
  std::string json_file;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) != "--json") {
      args.emplace_back(argv[i]);
    } else if (i + 1 < argc) {
      json_file = argv[++i];
    } else {
      std::fprintf(stderr, "membrane_kernels: --json needs a file\n");
      return 2;
    }
  }
  const std::string mesh_arg = args.size() > 0 ? args[0] : "300";
  const bool mesh_file = isMeshFile(mesh_arg);
  const int threads = args.size() > 1 ? std::atoi(args[1].c_str()) : 2;
  const int steps = args.size() > 2 ? std::atoi(args[2].c_str()) : 40;
  const std::string mode = args.size() > 3 ? args[3] : "all";
  if (mode != "all" && mode != "explicit" && mode != "law") {
    std::fprintf(stderr, "membrane_kernels: unknown mode '%s' (all, explicit or law)\n",
                 mode.c_str());
    return 2;
  }
  omp_set_num_threads(threads);
  Report report;
  report["mesh"] = mesh_arg;
  report["threads"] = threads;
  report["steps"] = steps;
  report["mode"] = mode;
  if (mode == "law") {
    lawMode(report, std::atoi(mesh_arg.c_str()), threads, steps);
    report.write(json_file);
    return 0;
  }
  const membrane::Model model = benchmarkCase(mesh_arg, mesh_file);
  const int triangles = static_cast<int>(model.mesh.triangles.size());
  std::printf("%s (%d triangles, %d DOF), threads = %d\n",
              mesh_file ? mesh_arg.c_str() : ("N = " + mesh_arg).c_str(), triangles,
              model.numDofs(), threads);
  report["triangles"] = triangles;
  report["dofs"] = model.numDofs();
  const bool all = mode != "explicit";
  const membrane::SparseMatrix K = membrane::assemble(model.mesh, model.sections, false).K;
  const Products spmv = products(report, K, all);
  if (all)
    newmark(report, model, steps, spmv.floor);
  explicitSteps(report, model, steps, spmv, all);
  report.write(json_file);
  return 0;
}
