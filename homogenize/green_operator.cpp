#include "homogenize/green_operator.hpp"

#include <cmath>

namespace lamina::homogenize {

GreenOperator::GreenOperator(const Grid& grid, double lambda0, double mu0, VectorFft& fft,
                             const Distribution& dist)
    : grid_(grid), lambda0_(lambda0), mu0_(mu0), fft_(fft), dist_(dist) {
  for (int d = 0; d < 3; ++d) {
    const int n = grid.n[static_cast<std::size_t>(d)];
    const int m = (d == 2) ? n / 2 + 1 : n; // r2c keeps half the last axis
    for (int k = 0; k < m; ++k) {
      const double half_xi = M_PI * k / n; // xi/2 with xi = 2 pi k / n
      sin_[d].push_back(std::sin(half_xi));
      cos_[d].push_back(std::cos(half_xi));
    }
  }
}

// The closed-form 3x3 solve on this rank's x-planes of the spectrum (type
// T: the transforms' precision; the factors and r^T z stay in double).
template <class T>
double GreenOperator::solveModes() const {
  T* w = fft_.spectrum<T>();
  const std::size_t chunk2 = 2 * fft_.chunkSize(); // T values between components
  const int nx = dist_.nx(), x0 = dist_.x0(), n1 = grid_.n[1], m2 = grid_.n[2] / 2 + 1;
  const double norm = 1.0 / static_cast<double>(grid_.size()); // FFTW is unnormalized
  const double beta = (lambda0_ + mu0_) / (lambda0_ + 2 * mu0_);
  const double norm_mu = norm / mu0_;
  const double h0 = grid_.h[0], h1 = grid_.h[1], h2 = grid_.h[2];
  // |q|^2 below this is a zero of q (cos(pi/2) is 6e-17, not 0)
  const double qmax2 = 4.0 * (1 / (h0 * h0) + 1 / (h1 * h1) + 1 / (h2 * h2));
  const double zero2 = 1e-20 * qmax2;
  const int n2 = grid_.n[2];
  double rz = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rz)
  for (int il = 0; il < nx; ++il)
    for (int j = 0; j < n1; ++j) {
      const std::size_t i = static_cast<std::size_t>(x0 + il);
      const double s0 = sin_[0][i], c0 = cos_[0][i];
      const double s1 = sin_[1][static_cast<std::size_t>(j)],
                   c1 = cos_[1][static_cast<std::size_t>(j)];
      // q = (A c2, B c2, Cz s2): the (i, j) factors hoisted out of the k loop
      const double A = 2 * s0 * c1 / h0, B = 2 * c0 * s1 / h1, Cz = 2 * c0 * c1 / h2;
      for (int k = 0; k < m2; ++k) {
        const double s2 = sin_[2][static_cast<std::size_t>(k)],
                     c2 = cos_[2][static_cast<std::size_t>(k)];
        const std::size_t idx = 2 * ((static_cast<std::size_t>(il) * n1 + j) * m2 + k);
        T* a = w + idx;
        T* b = w + chunk2 + idx;
        T* c = w + 2 * chunk2 + idx;
        const double q0 = A * c2, q1 = B * c2, q2 = Cz * s2;
        const double qq = q0 * q0 + q1 * q1 + q2 * q2;
        if (qq <= zero2) {
          a[0] = a[1] = b[0] = b[1] = c[0] = c[1] = 0;
          continue;
        }
        const double rq = 1.0 / qq; // one division per mode
        const double inv = norm_mu * rq, bq = beta * rq;
        // Parseval over the half spectrum: the modes 0 < k < n2/2 stand for
        // themselves and their conjugates
        const double weight = (k == 0 || 2 * k == n2) ? 1.0 : 2.0;
        double rz_here = 0;
        for (int part = 0; part < 2; ++part) {
          const double ra = a[part], rb = b[part], rc = c[part];
          const double dot = bq * (q0 * ra + q1 * rb + q2 * rc);
          const double za = inv * (ra - dot * q0), zb = inv * (rb - dot * q1),
                       zc = inv * (rc - dot * q2);
          a[part] = static_cast<T>(za);
          b[part] = static_cast<T>(zb);
          c[part] = static_cast<T>(zc);
          rz_here += ra * za + rb * zb + rc * zc;
        }
        rz += weight * rz_here;
      }
    }
  return rz;
}

template <class V>
double GreenOperator::apply(const V* r, V* z) const {
  fft_.forward(r);
  double rz = fft_.precision() == Precision::Single ? solveModes<float>() : solveModes<double>();
  fft_.backward(z);
  dist_.sum(&rz, 1);
  return rz;
}

template <class V>
double GreenOperator::step(V* r, double alpha, const V* w, V* x, V* p, double rz,
                           double rz_stop) const {
  fft_.forwardUpdate(r, alpha, w);
  double rz_new =
      fft_.precision() == Precision::Single ? solveModes<float>() : solveModes<double>();
  dist_.sum(&rz_new, 1);
  if (rz_new <= rz_stop) { // converged (every rank sees the same sum)
    if (x) {
      const std::size_t n = 3 * dist_.localSize();
      const V a = static_cast<V>(alpha);
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        x[i] += a * p[i];
    }
    return rz_new;
  }
  fft_.backwardUpdate(p, rz_new / rz, x, alpha);
  return rz_new;
}

#define LAMINA_GREEN_FIELDS(V)                                                                     \
  template double GreenOperator::apply<V>(const V*, V*) const;                                     \
  template double GreenOperator::step<V>(V*, double, const V*, V*, V*, double, double) const;
LAMINA_GREEN_FIELDS(double)
LAMINA_GREEN_FIELDS(float)
#undef LAMINA_GREEN_FIELDS

} // namespace lamina::homogenize
