#include "homogenize/dispersion.hpp"

#include "core/error.hpp"
#include "homogenize/fft.hpp"

#include <Eigen/Dense>

#include <cmath>
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
/// rotated gradient, its phase theta = (xi_1 + xi_2 + xi_3)/2, the
/// consistent-mass weight of the trilinear interpolant and the Parseval
/// weight of the half spectrum.
struct Mode {
  std::size_t index;
  Eigen::Vector3d q;
  double theta, mass, weight;
};

/// Calls f(Mode) for every mode of @p grid.
template <class F>
void forEachMode(const Grid& grid, F&& f) {
  const int n0 = grid.n[0], n1 = grid.n[1], n2 = grid.n[2], m2 = n2 / 2 + 1;
  auto xi = [](int k, int n) { return 2 * M_PI * k / n; };
  for (int i = 0; i < n0; ++i)
    for (int j = 0; j < n1; ++j)
      for (int k = 0; k < m2; ++k) {
        const double x0 = xi(i, n0), x1 = xi(j, n1), x2 = xi(k, n2);
        const double s0 = std::sin(x0 / 2), c0 = std::cos(x0 / 2);
        const double s1 = std::sin(x1 / 2), c1 = std::cos(x1 / 2);
        const double s2 = std::sin(x2 / 2), c2 = std::cos(x2 / 2);
        Mode m;
        m.index = (static_cast<std::size_t>(i) * n1 + j) * m2 + k;
        m.q = {2 * s0 * c1 * c2 / grid.h[0], 2 * c0 * s1 * c2 / grid.h[1],
               2 * c0 * c1 * s2 / grid.h[2]};
        m.theta = (x0 + x1 + x2) / 2;
        m.mass = (2 + std::cos(x0)) * (2 + std::cos(x1)) * (2 + std::cos(x2)) / 27;
        m.weight = (k == 0 || 2 * k == n2) ? 1.0 : 2.0;
        f(m);
      }
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

void DispersionAccumulator::addLoadCase(int k, const double* u) {
  LAMINA_CHECK(k >= 0 && k < 6, "load case ", k, " is not in 0..5");
  const std::size_t Nc = grid_.complexSize();
  const double NN = static_cast<double>(grid_.size()) * static_cast<double>(grid_.size());
  const Distribution serial = Distribution::serial(grid_);
  VectorFft fft(grid_, serial, 0, false, Precision::Double);
  fft.forward(u);
  const double* w = fft.spectrum<double>();
  const std::size_t chunk = fft.chunkSize(); // complex entries between components
  std::vector<Complex>& h = h_hat_[static_cast<std::size_t>(k)];
  h.assign(3 * Nc, Complex(0, 0));
  const Eigen::Matrix3d T = unitStrain(k);
  const double zero2 = zeroOfQ(grid_);
  double e2 = 0, r2 = 0, H2 = 0;
  forEachMode(grid_, [&](const Mode& m) {
    const Complex s = s_hat_[m.index];
    const double qq = m.q.squaredNorm();
    // e_hat = s T; |e_hat|^2 (Frobenius) per mode
    const double es = std::norm(s) * T.squaredNorm();
    e2 += m.weight * es;
    if (qq <= zero2) { // no periodic h reaches these modes: all residual
      r2 += m.weight * es;
      return;
    }
    // least squares: g = s v with v = A(q)^-1 T q, h_hat = g / (i e^{i theta})
    const Eigen::Vector3d Tq = T * m.q;
    const Eigen::Vector3d v = (2 / qq) * (Tq - m.q * (m.q.dot(Tq) / (2 * qq)));
    const Eigen::Matrix3d symqv = 0.5 * (m.q * v.transpose() + v * m.q.transpose());
    r2 += m.weight * std::norm(s) * (T - symqv).squaredNorm();
    const Complex to_h = Complex(0, -1) * std::polar(1.0, -m.theta); // 1 / (i e^{i theta})
    for (int c = 0; c < 3; ++c) {
      const std::size_t at = static_cast<std::size_t>(c) * Nc + m.index;
      const std::size_t in = 2 * (static_cast<std::size_t>(c) * chunk + m.index);
      const Complex Hc(w[in], w[in + 1]);
      H2 += m.weight * m.mass * std::norm(Hc);
      h[at] = Hc + to_h * s * v[c];
    }
  });
  const std::size_t kk = static_cast<std::size_t>(k);
  out_.residual[kk] = e2 > 0 ? std::sqrt(r2 / e2) : 0.0;
  out_.H_rms[kk] = std::sqrt(H2 / NN);
  have_[kk] = true;
  // eq. 38 for every pair with a case already in
  for (std::size_t J = 0; J < 6; ++J) {
    if (!have_[J])
      continue;
    const std::vector<Complex>& g = h_hat_[J];
    double sum = 0;
    forEachMode(grid_, [&](const Mode& m) {
      double dot = 0;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t at = c * Nc + m.index;
        dot += (h[at] * std::conj(g[at])).real();
      }
      sum += m.weight * m.mass * dot;
    });
    const double D = rho_bar_ * sum / NN;
    out_.D(static_cast<Eigen::Index>(kk), static_cast<Eigen::Index>(J)) = D;
    out_.D(static_cast<Eigen::Index>(J), static_cast<Eigen::Index>(kk)) = D;
  }
  out_.h_rms[kk] = std::sqrt(out_.D(k, k) / rho_bar_);
}

Dispersion DispersionAccumulator::result() const {
  for (std::size_t k = 0; k < 6; ++k)
    LAMINA_CHECK(have_[k], "dispersion: load case ", k + 1, " was not added");
  return out_;
}

} // namespace lamina::homogenize
