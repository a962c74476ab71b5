// Times the building blocks of one CG iteration of the homogenizer at N^3:
// the stiffness operator (A p), the Green preconditioner (3 r2c + 3 c2r
// FFTs and the closed-form 3x3 solve), one whole CG iteration (A p and the
// preconditioner with the fused vector updates, as the solver runs them) and
// the FFT floor (3 r2c + 3 c2r alone); prints the iteration over the floor.
// Also a load case's start residual b = -D^T C E: by the operator with u =
// 0 and as the solver forms it (start_residual.hpp: only next to interfaces).
// With single precision the fields and the operator are float, as in the
// solver at tol >= 1e-6.
// With a cell file it times that cell as `homogenize` builds it (composite
// voxels and all: building the cell and its voxel materials is timed too),
// else a centred 19 % sphere of the benchmark's two phases, staircase.
// Usage: homogenize_kernels N THREADS [measure|estimate [single|double [CELL]]]
#include "homogenize/cell_operator.hpp"
#include "homogenize/fft.hpp"
#include "homogenize/green_operator.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/library_entry.hpp"
#include "homogenize/start_residual.hpp"
#include "micro/cell.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/inclusion.hpp"
#include "micro/unit_cell.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

using namespace lamina;

// Times the operator, the preconditioner, one CG iteration and the FFT
// floor with CG vectors of type V.
template <class V>
void timeIteration(const homogenize::Grid& g, const homogenize::CellOperator& A,
                   const homogenize::StartResidual& b, const homogenize::GreenOperator& M,
                   homogenize::VectorFft& fft) {
  homogenize::AlignedArray<V> u(3 * g.size()), f(3 * g.size());
  for (std::size_t i = 0; i < u.size(); ++i)
    u.data()[i] = static_cast<V>(std::sin(0.001 * static_cast<double>(i)));
  const std::array<double, 6> E{0, 0, 0, 0, 0, 0};
  auto cpu = [] {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  };
  struct Timing {
    double wall, cpu;
  };
  auto time = [&](const char* what, auto&& fn) {
    fn();
    const int reps = 10;
    double best = 1e30;
    const double c0 = cpu();
    for (int r = 0; r < reps; ++r) {
      const auto a = std::chrono::steady_clock::now();
      fn();
      best = std::min(best,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
    }
    const Timing t{best, (cpu() - c0) / reps};
    std::printf("%-28s %8.2f ms wall (best of %d) %8.2f ms cpu (mean, all threads)\n", what,
                1e3 * t.wall, reps, 1e3 * t.cpu);
    return t;
  };
  time("operator A p", [&] { A.apply(u.data(), E, f.data(), nullptr); });
  time("stress pass only", [&] {
    std::array<double, 6> avg{};
    A.apply(u.data(), E, nullptr, &avg);
  });
  const std::array<double, 6> E1{1, 0, 0, 0, 0, 0};
  time("b by the operator (u = 0)", [&] {
    std::array<double, 6> avg{};
    A.apply(static_cast<const V*>(nullptr), E1, f.data(), &avg);
  });
  time("b next to interfaces only", [&] {
    std::array<double, 6> avg{};
    b.apply(E1, f.data(), avg);
  });
  std::printf("node rows next to an interface: %.1f %%\n", 100 * b.activeRowFraction());
  time("preconditioner M r", [&] { M.apply(u.data(), f.data()); });
  homogenize::AlignedArray<V> r(3 * g.size()), x(3 * g.size()), p(3 * g.size());
  std::copy(u.data(), u.data() + u.size(), r.data());
  std::copy(u.data(), u.data() + u.size(), p.data());
  std::fill(x.data(), x.data() + x.size(), V(0));
  // alpha tiny keeps r about constant, and the old r^T z at 1e3 times the new
  // one gives beta = 1e-3: r, x and p stay bounded (and normal, no
  // denormals) over the repetitions
  const double rz = 1e3 * M.apply(r.data(), f.data());
  const Timing iteration = time("CG iteration (A p + step)", [&] {
    double pw = 0;
    std::array<double, 6> sigma_p{};
    A.apply(p.data(), E, f.data(), &sigma_p, &pw);
    M.step(r.data(), 1e-12, f.data(), x.data(), p.data(), rz);
  });
  const Timing floor = time("3 x (r2c + c2r) + copies", [&] {
    fft.forward(u.data());
    fft.backward(f.data());
  });
  std::printf("CG iteration / FFT floor: %.2f wall, %.2f cpu\n", iteration.wall / floor.wall,
              iteration.cpu / floor.cpu);
}

int main(int argc, char** argv) {
  const int N = argc > 1 ? std::atoi(argv[1]) : 128;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const bool measure = argc > 3 && std::strcmp(argv[3], "measure") == 0;
  const bool single = argc > 4 && std::strcmp(argv[4], "single") == 0;
  omp_set_num_threads(threads);
  homogenize::Grid g;
  g.n = {N, N, N};
  g.h = {1.0 / N, 1.0 / N, 1.0 / N};
  std::vector<std::int32_t> map;
  std::vector<materials::Stiffness> C{materials::Stiffness::isotropic(156e6, 0.494),
                                      materials::Stiffness::isotropic(890e6, 0.491)};
  if (argc > 5) {
    const auto c0 = std::chrono::steady_clock::now();
    const micro::CellSpec spec = micro::readCell(argv[5], micro::lazyCatalog());
    const micro::UnitCell cell = micro::buildCell(spec, {N, N, N});
    const auto c1 = std::chrono::steady_clock::now();
    micro::VoxelMaterials vm =
        micro::voxelMaterials(cell, spec.stiffnessesAt(1.0), spec.densities());
    const auto c2 = std::chrono::steady_clock::now();
    std::printf("cell %s: build %.3f s, voxel materials %.3f s (%zu composite voxels)\n", argv[5],
                std::chrono::duration<double>(c1 - c0).count(),
                std::chrono::duration<double>(c2 - c1).count(), cell.composites.size());
    g = homogenize::gridOf(cell);
    map = std::move(vm.phase);
    C = std::move(vm.C);
  } else {
    micro::Inclusion s;
    s.phase = 1;
    s.semi.setConstant(0.357);
    s.center = Eigen::Vector3d(0.5, 0.5, 0.5);
    map = micro::voxelize({s}, g.n, Eigen::Vector3d::Ones());
  }
  double lambda0 = 0, mu0 = 0;
  homogenize::referenceMedium(C, lambda0, mu0);
  auto t0 = std::chrono::steady_clock::now();
  const auto dist = homogenize::Distribution::serial(g);
  homogenize::VectorFft fft(g, dist, threads, measure,
                            single ? homogenize::Precision::Single : homogenize::Precision::Double);
  const double plan_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto a0 = std::chrono::steady_clock::now();
  homogenize::CellOperator A(g, map, C, dist);
  std::printf("operator setup %.3f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - a0).count());
  homogenize::GreenOperator M(g, lambda0, mu0, fft, dist);
  std::printf("N = %d, threads = %d, planning %s, %s precision: %.2f s\n", N, threads,
              measure ? "FFTW_MEASURE" : "FFTW_ESTIMATE", single ? "single" : "double", plan_s);
  const homogenize::StartResidual b(g, map, C, dist);
  // the fields as the solver holds them: float with single-precision transforms
  if (single)
    timeIteration<float>(g, A, b, M, fft);
  else
    timeIteration<double>(g, A, b, M, fft);
  return 0;
}
