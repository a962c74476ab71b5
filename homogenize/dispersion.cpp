#include "homogenize/dispersion.hpp"

#include "core/error.hpp"
#include "homogenize/fft.hpp"

#include <Eigen/Dense>

#include <omp.h>

#include <cmath>
#include <complex>
#include <cstring>

namespace lamina::homogenize {

namespace {

/// The strain tensor of unit load case k (lamina order, engineering shear:
/// a unit gamma_xy is eps_xy = eps_yx = 1/2).
Eigen::Matrix3d unitStrain(int k) {
  static constexpr int a[6] = {0, 1, 2, 0, 1, 0}, b[6] = {0, 1, 2, 1, 2, 2};
  Eigen::Matrix3d T = Eigen::Matrix3d::Zero();
  const double v = k < 3 ? 1.0 : 0.5;
  T(a[k], b[k]) = v;
  T(b[k], a[k]) = v;
  return T;
}

/// One Fourier mode of the r2c half spectrum: the real vector q of the
/// rotated gradient, the phase factor e^{-i theta} with theta = (xi_1 + xi_2
/// + xi_3)/2, the consistent-mass weight of the trilinear interpolant and
/// the Parseval weight of the half spectrum.
struct Mode {
  std::size_t index;
  Eigen::Vector3d q;
  std::complex<double> shift; // e^{-i theta}
  double mass, weight;
};

/// Calls f(Mode, acc) for every mode of @p grid on the OpenMP threads, each
/// with its own @p count accumulators acc[0..count-1]; returns their sums
/// (the threads' partial sums added in thread order). The factors of each
/// axis (sin and cos of xi/2, e^{-i xi/2}, (2 + cos xi)/3) are tabulated
/// once: a mode costs products, no trigonometry.
template <class F>
std::vector<double> sumOverModes(const Grid& grid, std::size_t count, F&& f) {
  const int n[3] = {grid.n[0], grid.n[1], grid.n[2]};
  const int m2 = n[2] / 2 + 1;
  std::vector<double> sn[3], cs[3], mass[3];
  std::vector<std::complex<double>> shift[3];
  for (int d = 0; d < 3; ++d) {
    const int m = d == 2 ? m2 : n[d];
    for (int k = 0; k < m; ++k) {
      const double xi = 2 * M_PI * k / n[d];
      sn[d].push_back(std::sin(xi / 2));
      cs[d].push_back(std::cos(xi / 2));
      mass[d].push_back((2 + std::cos(xi)) / 3);
      shift[d].push_back(std::polar(1.0, -xi / 2));
    }
  }
  // per-thread accumulators, allocated before the region (nothing in it throws)
  std::vector<std::vector<double>> acc_of(static_cast<std::size_t>(omp_get_max_threads()),
                                          std::vector<double>(count, 0.0));
#pragma omp parallel
  {
    double* acc = acc_of[static_cast<std::size_t>(omp_get_thread_num())].data();
#pragma omp for schedule(static)
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < m2; ++k) {
          const auto I = static_cast<std::size_t>(i), J = static_cast<std::size_t>(j),
                     Kz = static_cast<std::size_t>(k);
          Mode m;
          m.index = (I * static_cast<std::size_t>(n[1]) + J) * static_cast<std::size_t>(m2) + Kz;
          m.q = {2 * sn[0][I] * cs[1][J] * cs[2][Kz] / grid.h[0],
                 2 * cs[0][I] * sn[1][J] * cs[2][Kz] / grid.h[1],
                 2 * cs[0][I] * cs[1][J] * sn[2][Kz] / grid.h[2]};
          m.shift = shift[0][I] * shift[1][J] * shift[2][Kz];
          m.mass = mass[0][I] * mass[1][J] * mass[2][Kz];
          m.weight = (k == 0 || 2 * k == n[2]) ? 1.0 : 2.0;
          f(m, acc);
        }
  }
  std::vector<double> total(count, 0.0);
  for (const auto& acc : acc_of)
    for (std::size_t a = 0; a < count; ++a)
      total[a] += acc[a];
  return total;
}

/// |q|^2 below this is a zero of q (cos(pi/2) is 6e-17, not 0), as in the
/// Green operator.
double zeroOfQ(const Grid& g) {
  return 1e-20 * 4.0 * (1 / (g.h[0] * g.h[0]) + 1 / (g.h[1] * g.h[1]) + 1 / (g.h[2] * g.h[2]));
}

} // namespace

DispersionAccumulator::DispersionAccumulator(const Grid& grid,
                                             const std::vector<std::int32_t>& phase,
                                             const std::vector<double>& density)
    : grid_(grid) {
  const std::size_t N = grid.size();
  LAMINA_CHECK(phase.size() == N, "phase map has ", phase.size(), " voxels, the grid ", N);
  std::vector<double> fraction(density.size(), 0.0);
  for (std::int32_t p : phase) {
    LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < density.size(), "phase index ", p,
                 " has no density");
    fraction[static_cast<std::size_t>(p)] += 1.0 / static_cast<double>(N);
  }
  for (std::size_t p = 0; p < density.size(); ++p)
    rho_bar_ += fraction[p] * density[p];
  LAMINA_CHECK(rho_bar_ > 0, "mean density must be positive");
  // Delta rho(y) / rho_bar = sum_p f_p (rho_p - rho(y)) / rho_bar (sum f_p = 1):
  // exactly zero when all phases have one density
  std::vector<double> s_of_phase(density.size(), 0.0);
  for (std::size_t q = 0; q < density.size(); ++q)
    for (std::size_t p = 0; p < density.size(); ++p)
      s_of_phase[q] += fraction[p] * (density[p] - density[q]) / rho_bar_;
  AlignedBuffer field(3 * N);
  std::memset(field.data(), 0, 3 * N * sizeof(double));
  for (std::size_t v = 0; v < N; ++v)
    field.data()[v] = s_of_phase[static_cast<std::size_t>(phase[v])];
  const Distribution serial = Distribution::serial(grid);
  VectorFft fft(grid, serial, 0, false, Precision::Double);
  fft.forward(field.data());
  const std::size_t Nc = grid.complexSize();
  const double* w = fft.spectrum<double>(); // component 0 first
  s_hat_.resize(Nc);
  for (std::size_t i = 0; i < Nc; ++i)
    s_hat_[i] = {w[2 * i], w[2 * i + 1]};
}

std::vector<std::complex<double>> DispersionAccumulator::spectrum(const double* u) const {
  const std::size_t Nc = grid_.complexSize();
  const Distribution serial = Distribution::serial(grid_);
  VectorFft fft(grid_, serial, 0, false, Precision::Double);
  fft.forward(u);
  const double* w = fft.spectrum<double>();
  const std::size_t chunk = fft.chunkSize(); // complex entries between components
  std::vector<Complex> out(3 * Nc);
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < Nc; ++i)
      out[c * Nc + i] = Complex(w[2 * (c * chunk + i)], w[2 * (c * chunk + i) + 1]);
  return out;
}

void DispersionAccumulator::addLoadCase(int k, const double* u) {
  LAMINA_CHECK(k >= 0 && k < 6, "load case ", k, " is not in 0..5");
  const std::size_t Nc = grid_.complexSize();
  const double NN = static_cast<double>(grid_.size()) * static_cast<double>(grid_.size());
  const std::vector<Complex> H = spectrum(u);
  const std::size_t kk = static_cast<std::size_t>(k);
  std::vector<Complex>& h = h_hat_[kk];
  h.assign(3 * Nc, Complex(0, 0));
  const Eigen::Matrix3d T = unitStrain(k);
  const double zero2 = zeroOfQ(grid_);
  // sums: |e|^2, |residual|^2, |H|^2 (mass-weighted)
  const auto sums = sumOverModes(grid_, 3, [&](const Mode& m, double* acc) {
    const Complex s = s_hat_[m.index];
    const double qq = m.q.squaredNorm();
    // e_hat = s T; |e_hat|^2 (Frobenius) per mode
    const double es = std::norm(s) * T.squaredNorm();
    acc[0] += m.weight * es;
    if (qq <= zero2) { // no periodic h reaches these modes: all residual
      acc[1] += m.weight * es;
      return;
    }
    // least squares: g = s v with v = A(q)^-1 T q, h_hat = g / (i e^{i theta})
    const Eigen::Vector3d Tq = T * m.q;
    const Eigen::Vector3d v = (2 / qq) * (Tq - m.q * (m.q.dot(Tq) / (2 * qq)));
    const Eigen::Matrix3d symqv = 0.5 * (m.q * v.transpose() + v * m.q.transpose());
    acc[1] += m.weight * std::norm(s) * (T - symqv).squaredNorm();
    const Complex to_h = Complex(0, -1) * m.shift; // 1 / (i e^{i theta})
    for (int c = 0; c < 3; ++c) {
      const std::size_t at = static_cast<std::size_t>(c) * Nc + m.index;
      const Complex Hc = H[at];
      acc[2] += m.weight * m.mass * std::norm(Hc);
      h[at] = Hc + to_h * s * v[c];
    }
  });
  out_.residual[kk] = sums[0] > 0 ? std::sqrt(sums[1] / sums[0]) : 0.0;
  out_.H_rms[kk] = std::sqrt(sums[2] / NN);
  have_[kk] = true;
  // eq. 38 for every pair with a case already in, all in one pass over the modes
  const std::vector<Complex>* g[6] = {};
  for (std::size_t J = 0; J < 6; ++J)
    g[J] = have_[J] ? &h_hat_[J] : nullptr;
  const auto pair = sumOverModes(grid_, 6, [&](const Mode& m, double* acc) {
    for (std::size_t J = 0; J < 6; ++J) {
      if (!g[J])
        continue;
      double dot = 0;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t at = c * Nc + m.index;
        dot += (h[at] * std::conj((*g[J])[at])).real();
      }
      acc[J] += m.weight * m.mass * dot;
    }
  });
  for (std::size_t J = 0; J < 6; ++J) {
    if (!have_[J])
      continue;
    const double D = rho_bar_ * pair[J] / NN;
    out_.D(static_cast<Eigen::Index>(kk), static_cast<Eigen::Index>(J)) = D;
    out_.D(static_cast<Eigen::Index>(J), static_cast<Eigen::Index>(kk)) = D;
  }
  out_.h_rms[kk] = std::sqrt(out_.D(k, k) / rho_bar_);
}

InfluenceAverages DispersionAccumulator::addInfluence(const double* S) {
  for (std::size_t k = 0; k < 6; ++k)
    LAMINA_CHECK(have_[k], "influence function before load case ", k + 1, " was added");
  const std::size_t Nc = grid_.complexSize();
  const double NN = static_cast<double>(grid_.size()) * static_cast<double>(grid_.size());
  std::vector<Complex> s = spectrum(S);
  const std::size_t before = s_hat_of_.size();
  const double zero2 = zeroOfQ(grid_);
  // accumulators: 6 with h, then one per earlier function, then itself
  const auto sums = sumOverModes(grid_, 6 + before + 1, [&](const Mode& m, double* acc) {
    if (m.q.squaredNorm() <= zero2) { // mean and hourglass modes: dropped, as h's
      for (std::size_t c = 0; c < 3; ++c)
        s[c * Nc + m.index] = Complex(0, 0);
      return;
    }
    const double f = m.weight * m.mass;
    auto dot = [&](const std::vector<Complex>& g) {
      double d = 0;
      for (std::size_t c = 0; c < 3; ++c)
        d += (g[c * Nc + m.index] * std::conj(s[c * Nc + m.index])).real();
      return d;
    };
    for (std::size_t I = 0; I < 6; ++I)
      acc[I] += f * dot(h_hat_[I]);
    for (std::size_t b = 0; b < before; ++b)
      acc[6 + b] += f * dot(s_hat_of_[b]);
    acc[6 + before] += f * dot(s);
  });
  InfluenceAverages out;
  for (std::size_t I = 0; I < 6; ++I)
    out.with_h[I] = rho_bar_ * sums[I] / NN;
  for (std::size_t b = 0; b <= before; ++b)
    out.with_s.push_back(rho_bar_ * sums[6 + b] / NN);
  s_hat_of_.push_back(std::move(s));
  return out;
}

Dispersion DispersionAccumulator::result() const {
  for (std::size_t k = 0; k < 6; ++k)
    LAMINA_CHECK(have_[k], "dispersion: load case ", k + 1, " was not added");
  return out_;
}

} // namespace lamina::homogenize
