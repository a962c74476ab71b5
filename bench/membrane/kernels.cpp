// Times the building blocks of a membrane step on the benchmark case
// (bench/membrane/bench.toml: N x N squares, 2 triangles each, centre strike,
// tau = 0.4 h_el / c_S): one product with the linear model's K in each storage
// (scalar CSR, plain 3x3 blocks = the memory floor of an assembled K, shared
// stencil rows), the Newmark step of the linear model (K u~ plus the CG
// solve), and one explicit (central-difference) step of the large-deflection
// fabric model and of the linear model, with their ratios to the SpMVs.
// Wall times are the best of the repetitions (the machine is shared: the
// best is the least disturbed), CPU times the mean over all threads.
// Usage: membrane_kernels N|MESH THREADS [STEPS] [all|explicit|law]
//   MESH: a .msh or .geo file instead of N: bench/membrane/bench-gmsh.toml
//        on that mesh (run.sh makes the unstructured benchmark square)
//   explicit: only the SpMV floor and the explicit steps (large meshes)
//   law: the explicit step of bench/membrane/gvbo.toml (N x N polyurea
//        sheet) with a GVBO section against the same sheet elastic at the
//        GVBO rest moduli, and their ratio (bench/membrane/gvbo.sh)
#include "membrane/integrators/step_solver.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/model/block_matrix.hpp"
#include "membrane/simulation.hpp"
#include "timing.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <ctime>
#include <string>
#include <vector>

using namespace lamina;

namespace {

using bench::timeIt;
using bench::Timing;

/// Prints a / b for the best wall and the CPU times.
void ratio(const char* what, Timing a, Timing b) {
  std::printf("  %-32s %.2f (best wall)  %.2f (cpu)\n", what, a.best / b.best, a.cpu / b.cpu);
}

/// The explicit step of bench/membrane/gvbo.toml at N x N with the section of
/// catalog material @p material, whose law must be linear iff @p linear
/// (else it exits 1: a timing of the wrong path is worse than none); prints
/// the line and @return its timing.
Timing lawStep(int N, int steps, const char* material, bool linear, const char* what) {
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
  return timeIt(what, steps, [&] { sim.step(); });
}

/// `law` mode: GVBO sheet against the elastic sheet, best wall and CPU per step.
int lawMode(int N, int threads, int steps) {
  std::printf("N = %d (%d triangles), threads = %d, polyurea sheet (bench/membrane/gvbo.toml)\n",
              N, 2 * N * N, threads);
  const Timing elastic = lawStep(N, steps, "polyurea-elastic-rest", true, "explicit step, elastic");
  const Timing gvbo = lawStep(N, steps, "polyurea-gvbo", false, "explicit step, GVBO");
  ratio("GVBO step / elastic step", gvbo, elastic);
  std::printf("  per element and step: GVBO %.3f us wall, %.3f us cpu\n",
              1e6 * gvbo.best / (2.0 * N * N), 1e6 * gvbo.cpu / (2.0 * N * N));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  const std::string mesh_arg = argc > 1 ? argv[1] : "300";
  const bool mesh_file = mesh_arg.size() > 4 && (mesh_arg.substr(mesh_arg.size() - 4) == ".msh" ||
                                                 mesh_arg.substr(mesh_arg.size() - 4) == ".geo");
  const int N = mesh_file ? 0 : std::atoi(mesh_arg.c_str());
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 40;
  const bool all = !(argc > 4 && std::strcmp(argv[4], "explicit") == 0);
  omp_set_num_threads(threads);
  if (argc > 4 && std::strcmp(argv[4], "law") == 0)
    return lawMode(N, threads, steps);
  const double c = std::sqrt(1e9 / (2 * 1.3) / 1000), dt = mesh_file ? 4.3e-6 : 0.4 / N / c;
  std::vector<std::string> set{"time.dt=" + std::to_string(dt),
                               "time.t_end=" + std::to_string(1000 * dt)};
  set.push_back(mesh_file ? "mesh.file=\"" + std::filesystem::absolute(mesh_arg).string() + "\""
                          : "mesh.nx=" + std::to_string(N));
  const membrane::Model model =
      membrane::readCase(mesh_file ? LAMINA_SOURCE_DIR "/bench/membrane/bench-gmsh.toml"
                                   : LAMINA_SOURCE_DIR "/bench/membrane/bench.toml",
                         set, {"/nonexistent/library.toml", ""});
  std::printf("%s (%d triangles, %d DOF), threads = %d\n",
              mesh_file ? mesh_arg.c_str() : ("N = " + std::to_string(N)).c_str(),
              static_cast<int>(model.mesh.triangles.size()), model.numDofs(), threads);

  const membrane::SparseMatrix K = membrane::assemble(model.mesh, model.sections, false).K;
  Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows()), y(K.rows());
  const int reps = 30;
  const membrane::BlockMatrix plain(K, false);
  const Timing floor = timeIt("SpMV K, 3x3 blocks (floor)", reps, [&] { plain.multiply(x, y); });
  const membrane::BlockMatrix shared(K);
  std::printf("  (shared stencil rows: %d stored rows)\n", shared.sharedRows());
  const Timing stencil =
      timeIt("SpMV K, shared rows, interleaved", reps, [&] { shared.multiply(x, y); });
  if (all) {
    timeIt("SpMV K, scalar CSR", reps, [&] { membrane::multiply(K, x, y); });
    Eigen::VectorXd xs = x, ys = y;
    timeIt("SpMV K, shared rows, planar", reps, [&] {
#pragma omp parallel
      {
        const int n = shared.nodes();
        const int t = omp_get_thread_num(), nt = omp_get_num_threads();
        shared.multiplyPlanar(xs.data(), ys.data(), n * t / nt, n * (t + 1) / nt);
      }
    });
    membrane::Simulation sim(model);
    const membrane::SolverStats st0 = sim.integrator().stats();
    timeIt("Newmark step (CG)", steps, [&] { sim.step(); });
    const membrane::SolverStats st1 = sim.integrator().stats();
    std::printf("  (CG iterations per step: %.1f)\n",
                double(st1.iterations - st0.iterations) / double(st1.solves - st0.solves));
  }

  // Explicit steps (dt = safety x stable step), the strike keeps them moving.
  membrane::Model fabric = model;
  fabric.kind = membrane::ModelKind::LargeDeflection;
  fabric.time.integrator = membrane::IntegratorKind::Explicit;
  fabric.time.dt = 0;
  {
    membrane::Simulation sim(fabric);
    Eigen::VectorXd f;
    const Timing force =
        timeIt("fabric internal force", reps, [&] { sim.structure().internalForce(sim.u(), f); });
    const Timing step = timeIt("explicit step, large deflection", steps, [&] { sim.step(); });
    ratio("large-deflection step / floor", step, floor);
    ratio("large-deflection step / stencil", step, stencil);
    ratio("internal force / floor", force, floor);
  }
  if (all) {
    membrane::Model linear = fabric;
    linear.kind = membrane::ModelKind::Linear;
    linear.time.lumped = true;
    membrane::Simulation sim(linear);
    const Timing step = timeIt("explicit step, linear", steps, [&] { sim.step(); });
    ratio("linear step / floor", step, floor);
    ratio("linear step / stencil", step, stencil);
  }
  return 0;
}
