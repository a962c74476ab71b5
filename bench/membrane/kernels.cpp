// Times the building blocks of a membrane step on the benchmark case
// (bench/membrane/bench.toml: N x N squares, 2 triangles each, centre strike,
// tau = 0.4 h_el / c_S): one product with the linear model's K in each storage
// (scalar CSR, plain 3x3 blocks = the memory floor of an assembled K, shared
// stencil rows), and the Newmark step of the linear model (K u~ plus the CG
// solve). Wall times are the best of the repetitions (the machine is shared:
// the best is the least disturbed), CPU times the mean over all threads.
// Usage: membrane_kernels N THREADS [STEPS]
#include "membrane/integrators/block_matrix.hpp"
#include "membrane/integrators/step_solver.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

using namespace lamina;

namespace {

double cpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Runs @p fn @p reps times; prints best and median wall, mean CPU (ms).
template <class F>
void timeIt(const char* what, int reps, F&& fn) {
  fn(); // warm caches and first-touch pages
  std::vector<double> wall;
  const double c0 = cpuSeconds();
  for (int r = 0; r < reps; ++r) {
    const double a = wallSeconds();
    fn();
    wall.push_back(wallSeconds() - a);
  }
  const double cpu = (cpuSeconds() - c0) / reps;
  std::sort(wall.begin(), wall.end());
  std::printf("%-34s best %8.3f ms  median %8.3f ms  cpu %8.3f ms\n", what, 1e3 * wall.front(),
              1e3 * wall[wall.size() / 2], 1e3 * cpu);
}

} // namespace

int main(int argc, char** argv) {
  const int N = argc > 1 ? std::atoi(argv[1]) : 300;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 40;
  omp_set_num_threads(threads);
  const double c = std::sqrt(1e9 / (2 * 1.3) / 1000), dt = 0.4 / N / c;
  const std::vector<std::string> set{"mesh.nx=" + std::to_string(N),
                                     "time.dt=" + std::to_string(dt),
                                     "time.t_end=" + std::to_string(1000 * dt)};
  const membrane::Model model = membrane::readCase(LAMINA_SOURCE_DIR "/bench/membrane/bench.toml",
                                                   set, {"/nonexistent/library.toml", ""});
  std::printf("N = %d (%d triangles, %d DOF), threads = %d\n", N,
              static_cast<int>(model.mesh.triangles.size()), model.numDofs(), threads);

  membrane::Simulation sim(model);
  const membrane::SparseMatrix& K = sim.K();
  Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows()), y(K.rows());
  const int reps = 30;
  timeIt("SpMV K, scalar CSR", reps, [&] { membrane::multiply(K, x, y); });
  const membrane::BlockMatrix plain(K, false), shared(K);
  timeIt("SpMV K, 3x3 blocks (floor)", reps, [&] { plain.multiply(x, y); });
  std::printf("  (shared stencil rows: %d stored rows)\n", shared.sharedRows());
  timeIt("SpMV K, shared rows, interleaved", reps, [&] { shared.multiply(x, y); });
  Eigen::VectorXd xs = x, ys = y;
  timeIt("SpMV K, shared rows, planar", reps, [&] {
#pragma omp parallel
    {
      const int n = shared.nodes();
      const int t = omp_get_thread_num(), nt = omp_get_num_threads();
      shared.multiplyPlanar(xs.data(), ys.data(), n * t / nt, n * (t + 1) / nt);
    }
  });
  const membrane::SolverStats st0 = sim.integrator().stats();
  timeIt("Newmark step (CG)", steps, [&] { sim.step(); });
  const membrane::SolverStats st1 = sim.integrator().stats();
  std::printf("  (CG iterations per step: %.1f)\n",
              double(st1.iterations - st0.iterations) / double(st1.solves - st0.solves));
  return 0;
}
