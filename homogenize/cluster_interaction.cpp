#include "homogenize/cluster_interaction.hpp"

#include "core/error.hpp"

#include <fftw3.h>
#include <omp.h>

#include <cmath>
#include <complex>
#include <memory>

namespace lamina::homogenize {

namespace {

using materials::Matrix6;

/// blocks of Fourier modes summed apart (thread-count-free sums)
constexpr int kBlocks = 8;

/// (i, j) of lamina-order component c: xx, yy, zz, xy, yz, xz
constexpr int kPair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};

/// The symbols Ga(n), Gb(n) of the unit vector @p n in the mixed Voigt form
/// of the file comment (rows engineering strain, columns stress).
void symbols(const double n[3], Matrix6& Ga, Matrix6& Gb) {
  for (int I = 0; I < 6; ++I) {
    const int i = kPair[I][0], j = kPair[I][1];
    const double fI = I < 3 ? 1.0 : 2.0;
    for (int J = 0; J < 6; ++J) {
      const int k = kPair[J][0], l = kPair[J][1];
      const double f = fI * (J < 3 ? 1.0 : 2.0);
      const double a = (i == k) * n[j] * n[l] + (i == l) * n[j] * n[k] + (j == k) * n[i] * n[l] +
                       (j == l) * n[i] * n[k];
      Ga(I, J) = 0.25 * f * a;
      Gb(I, J) = f * n[i] * n[j] * n[k] * n[l];
    }
  }
}

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};

/// The half spectra of every partition's indicator, mode-major:
/// chi[m * n + I] (unnormalized r2c transforms, FFTW_ESTIMATE plans).
std::vector<std::complex<double>>
indicatorSpectra(const Grid& grid, const std::vector<std::int32_t>& label, std::size_t n) {
  const std::size_t N = grid.size(), Nc = grid.complexSize();
  std::unique_ptr<double, FftwFree> in(static_cast<double*>(fftw_malloc(sizeof(double) * N)));
  std::unique_ptr<fftw_complex, FftwFree> out(
      static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * Nc)));
  LAMINA_CHECK(in && out, "cluster interaction: out of memory for the transforms");
  fftw_plan plan =
      fftw_plan_dft_r2c_3d(grid.n[0], grid.n[1], grid.n[2], in.get(), out.get(), FFTW_ESTIMATE);
  LAMINA_CHECK(plan != nullptr, "cluster interaction: FFTW could not plan the transform");
  std::vector<std::complex<double>> chi(n * Nc);
  for (std::size_t I = 0; I < n; ++I) {
    for (std::size_t v = 0; v < N; ++v)
      in.get()[v] = label[v] == static_cast<std::int32_t>(I) ? 1.0 : 0.0;
    fftw_execute(plan);
    for (std::size_t m = 0; m < Nc; ++m)
      chi[m * n + I] = {out.get()[m][0], out.get()[m][1]};
  }
  fftw_destroy_plan(plan);
  return chi;
}

/// Adds to @p sa, @p sb (one per pair I <= J) the symbols of the modes
/// [@p first, @p last) of @p grid weighted by the pair products of the
/// indicator spectra @p chi (mode-major, @p n per mode).
void accumulateModes(const Grid& grid, const std::vector<std::complex<double>>& chi, std::size_t n,
                     long first, long last, std::vector<Matrix6>& sa, std::vector<Matrix6>& sb) {
  const int n1 = grid.n[1], n2 = grid.n[2], m2 = n2 / 2 + 1;
  const double h0 = grid.h[0], h1 = grid.h[1], h2 = grid.h[2];
  // |q|^2 below this is a zero of q (cos(pi/2) is 6e-17, not 0)
  const double zero2 = 1e-20 * 4.0 * (1 / (h0 * h0) + 1 / (h1 * h1) + 1 / (h2 * h2));
  Matrix6 Ga, Gb;
  for (long mi = first; mi < last; ++mi) {
    const std::size_t m = static_cast<std::size_t>(mi);
    const int k = static_cast<int>(m % static_cast<std::size_t>(m2));
    const int j =
        static_cast<int>((m / static_cast<std::size_t>(m2)) % static_cast<std::size_t>(n1));
    const int i =
        static_cast<int>(m / (static_cast<std::size_t>(m2) * static_cast<std::size_t>(n1)));
    const double x0 = M_PI * i / grid.n[0], x1 = M_PI * j / n1, x2 = M_PI * k / n2;
    const double s0 = std::sin(x0), c0 = std::cos(x0), s1 = std::sin(x1), c1 = std::cos(x1),
                 s2 = std::sin(x2), c2 = std::cos(x2);
    const double q[3] = {2 * s0 * c1 * c2 / h0, 2 * c0 * s1 * c2 / h1, 2 * c0 * c1 * s2 / h2};
    const double qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    if (qq <= zero2)
      continue; // the mean and the hourglass modes carry no strain
    const double r = 1 / std::sqrt(qq);
    const double nv[3] = {q[0] * r, q[1] * r, q[2] * r};
    symbols(nv, Ga, Gb);
    // the modes 0 < k < n2/2 stand for themselves and their conjugates
    const double w = (k == 0 || 2 * k == n2) ? 1.0 : 2.0;
    const std::complex<double>* z = &chi[m * n];
    std::size_t p = 0;
    for (std::size_t I = 0; I < n; ++I)
      for (std::size_t J = I; J < n; ++J, ++p) {
        const double c = w * (z[I].real() * z[J].real() + z[I].imag() * z[J].imag());
        sa[p].noalias() += c * Ga;
        sb[p].noalias() += c * Gb;
      }
  }
}

} // namespace

ClusterInteraction clusterInteraction(const Grid& grid, const std::vector<std::int32_t>& label,
                                      const std::vector<std::size_t>& voxels, int threads) {
  const std::size_t N = grid.size(), Nc = grid.complexSize(), n = voxels.size();
  LAMINA_CHECK(label.size() == N, "cluster interaction: ", label.size(), " labels for ", N,
               " voxels");
  std::vector<std::size_t> count(n, 0);
  for (std::int32_t l : label) {
    LAMINA_CHECK(l >= 0 && static_cast<std::size_t>(l) < n, "cluster interaction: label ", l,
                 " outside the ", n, " partitions");
    ++count[static_cast<std::size_t>(l)];
  }
  for (std::size_t I = 0; I < n; ++I)
    LAMINA_CHECK(voxels[I] > 0 && voxels[I] == count[I], "cluster interaction: partition ", I,
                 " is said to have ", voxels[I], " voxels but has ", count[I]);
  // 1. the half spectrum of every partition's indicator
  const std::vector<std::complex<double>> chi = indicatorSpectra(grid, label, n);
  // 2. per mode the symbols, summed over pairs I <= J (the pair sum is
  // symmetric in I, J)
  const std::size_t pairs = n * (n + 1) / 2;
  // in kBlocks fixed blocks of modes, each summed on its own and the blocks
  // added in order: the same sums with any number of threads
  const long modes = static_cast<long>(Nc);
  std::vector<std::vector<Matrix6>> SA(kBlocks), SB(kBlocks);
#pragma omp parallel for schedule(static, 1)                                                       \
    num_threads(threads > 0 ? threads : omp_get_max_threads())
  for (int block = 0; block < kBlocks; ++block) {
    SA[static_cast<std::size_t>(block)].assign(pairs, Matrix6::Zero());
    SB[static_cast<std::size_t>(block)].assign(pairs, Matrix6::Zero());
    accumulateModes(grid, chi, n, modes * block / kBlocks, modes * (block + 1) / kBlocks,
                    SA[static_cast<std::size_t>(block)], SB[static_cast<std::size_t>(block)]);
  }
  for (int block = 1; block < kBlocks; ++block)
    for (std::size_t p = 0; p < pairs; ++p) {
      SA[0][p] += SA[static_cast<std::size_t>(block)][p];
      SB[0][p] += SB[static_cast<std::size_t>(block)][p];
    }
  // 3. normalized per row partition: 1 / (N_I N)
  ClusterInteraction res;
  res.Ga.assign(n * n, Matrix6::Zero());
  res.Gb.assign(n * n, Matrix6::Zero());
  std::size_t p = 0;
  for (std::size_t I = 0; I < n; ++I)
    for (std::size_t J = I; J < n; ++J, ++p) {
      const double dN = static_cast<double>(N);
      const double sI = 1 / (static_cast<double>(voxels[I]) * dN);
      const double sJ = 1 / (static_cast<double>(voxels[J]) * dN);
      res.Ga[I * n + J] = sI * SA[0][p];
      res.Gb[I * n + J] = sI * SB[0][p];
      res.Ga[J * n + I] = sJ * SA[0][p];
      res.Gb[J * n + I] = sJ * SB[0][p];
    }
  return res;
}

} // namespace lamina::homogenize
