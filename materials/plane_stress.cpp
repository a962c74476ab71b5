#include "materials/plane_stress.hpp"

#include "core/error.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lamina::materials {

namespace {

constexpr std::array<int, 3> kInPlane{0, 1, 3}; // xx, yy, xy in lamina order
constexpr std::array<int, 3> kOut{2, 4, 5};     // zz, yz, xz

/// Fixed-size matrices of the N = 3 + n_free unknowns (planeStressUpdate
/// dispatches on N once, so every product and LU below is unrolled).
template <int N>
using MatB = Eigen::Matrix<double, 6, N>;
template <int N>
using MatK = Eigen::Matrix<double, N, N>;
template <int N>
using VecZ = Eigen::Matrix<double, N, 1>;

/// @return E_p v: [xx, yy, xy] placed in lamina order
Vector6 placeInPlane(const Eigen::Vector3d& v) {
  Vector6 out = Vector6::Zero();
  for (std::size_t i = 0; i < 3; ++i)
    out[kInPlane[i]] = v[static_cast<Eigen::Index>(i)];
  return out;
}

/// B of the file comment: zz, yz, xz unit columns, then the free directions.
template <int N>
MatB<N> constraintBasis(const PlaneStressStep& s) {
  MatB<N> B = MatB<N>::Zero();
  for (std::size_t i = 0; i < 3; ++i)
    B(kOut[i], static_cast<Eigen::Index>(i)) = 1;
  for (int k = 0; k < N - 3; ++k) // N - 3 = s.n_free
    B.col(3 + k) = placeInPlane(s.free_dir[static_cast<std::size_t>(k)]);
  return B;
}

void checkStep(const PlaneStressStep& s) {
  LAMINA_CHECK(s.n_free >= 0 && s.n_free <= 3, "plane stress: ", s.n_free,
               " free directions (0 to 3 in a plane)");
  LAMINA_CHECK(s.lambda3_n > 0 && s.J2_n > 0 && s.J2 > 0,
               "plane stress: thickness stretch and area ratios must be positive (lambda3_n = ",
               s.lambda3_n, ", J2_n = ", s.J2_n, ", J2 = ", s.J2, ")");
  if (s.n_free == 0)
    return;
  // Gram determinant of the normalized directions: 1 for orthogonal, 0 for dependent
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3> D(3, s.n_free);
  for (int k = 0; k < s.n_free; ++k) {
    const Eigen::Vector3d& d = s.free_dir[static_cast<std::size_t>(k)];
    LAMINA_CHECK(d.allFinite() && d.norm() > 0, "plane stress: free direction ", k + 1,
                 " is zero or not finite");
    D.col(k) = d / d.norm();
  }
  const double gram = (D.transpose() * D).determinant();
  LAMINA_CHECK(gram > 1e-12, "plane stress: the free directions are linearly dependent");
}

/// The law's step at the unknowns @p z.
template <int N>
PointStep lawStep(const PlaneStressStep& s, const Vector6& deps_imposed, const MatB<N>& B,
                  const VecZ<N>& z) {
  PointStep ps;
  ps.eps_n = s.eps_n;
  ps.eps = s.eps_n + deps_imposed + B * z;
  ps.J_n = s.J2_n * s.lambda3_n;
  ps.J = s.J2 * midpointThicknessStretch(s.lambda3_n, z[0]);
  ps.dt = s.dt;
  return ps;
}

/// d sigma_p / d eps_p = T_pp - E_p^T T B (B^T T B)^-1 B^T T E_p.
template <int N>
Eigen::Matrix3d condensedTangent(const Matrix6& T, const MatB<N>& B) {
  Eigen::Matrix<double, 6, 3> TE;
  for (std::size_t j = 0; j < 3; ++j)
    TE.col(static_cast<Eigen::Index>(j)) = T.col(kInPlane[j]);
  const MatK<N> K = B.transpose() * T * B;
  const Eigen::Matrix<double, N, 3> X = K.partialPivLu().solve(B.transpose() * TE);
  const Eigen::Matrix<double, 6, 3> full = TE - T * B * X;
  Eigen::Matrix3d out;
  for (std::size_t i = 0; i < 3; ++i)
    out.row(static_cast<Eigen::Index>(i)) = full.row(kInPlane[i]);
  return out;
}

/// Fills eps, lambda3, amplitudes of @p r from the unknowns @p z.
template <int N>
void storeUnknowns(const PlaneStressStep& s, const PointStep& ps, const VecZ<N>& z,
                   PlaneStressResult& r) {
  r.eps = ps.eps;
  r.lambda3 = midpointThicknessStretch(s.lambda3_n, z[0]);
  for (int k = 0; k < N - 3; ++k) // N - 3 = s.n_free
    r.amplitude[static_cast<std::size_t>(k)] = z[3 + k];
}

/// max |B^T sigma| with the free rows divided by |d_k|.
template <int N>
double constrainedStress(const PlaneStressStep& s, const MatB<N>& B, const Vector6& sigma) {
  VecZ<N> r = B.transpose() * sigma;
  for (int k = 0; k < N - 3; ++k) // N - 3 = s.n_free
    r[3 + k] /= s.free_dir[static_cast<std::size_t>(k)].norm();
  return r.cwiseAbs().maxCoeff();
}

template <int N>
PlaneStressResult linearStep(const ConstitutiveLaw& law, const PlaneStressStep& s,
                             const Vector6& deps_imposed, const MatB<N>& B, bool want_tangent) {
  const Matrix6 C = law.elasticStiffness().matrix();
  const MatK<N> K = B.transpose() * C * B;
  const VecZ<N> z = -K.partialPivLu().solve(B.transpose() * (C * (s.eps_n + deps_imposed)));
  const PointStep ps = lawStep(s, deps_imposed, B, z);
  PlaneStressResult r;
  storeUnknowns(s, ps, z, r);
  r.sigma = C * ps.eps;
  r.residual = constrainedStress(s, B, r.sigma);
  LAMINA_CHECK(r.sigma.allFinite(), "plane stress: the stress is not finite");
  if (want_tangent)
    r.tangent = condensedTangent(C, B);
  return r;
}

/// planeStressUpdate() with N = 3 + s.n_free unknowns (checked by the caller).
template <int N>
PlaneStressResult update(const ConstitutiveLaw& law, const PlaneStressStep& s,
                         const double* state_n, double* state, bool want_tangent,
                         double tolerance) {
  const MatB<N> B = constraintBasis<N>(s);
  const Vector6 deps_imposed = placeInPlane(s.deps_p);
  if (law.isLinear())
    return linearStep(law, s, deps_imposed, B, want_tangent);
  PlaneStressResult own;
  if (!want_tangent && law.planeStressStep(s, state_n, state, tolerance, own))
    return own;

  // the law reads state_n at every iterate: keep a copy when it is overwritten
  std::vector<double> copy;
  if (state == state_n && law.stateSize() > 0) {
    copy.assign(state_n, state_n + law.stateSize());
    state_n = copy.data();
  }
  const Matrix6 C0 = law.elasticStiffness(s.J2_n * s.lambda3_n).matrix();
  const double maxC0 = C0.cwiseAbs().maxCoeff();
  VecZ<N> z = -(B.transpose() * C0 * B).partialPivLu().solve(B.transpose() * (C0 * deps_imposed));
  z[0] = std::clamp(z[0], -kMaxThicknessIncrement, kMaxThicknessIncrement);

  PlaneStressResult r;
  Matrix6 T;
  for (int it = 0;; ++it) {
    const PointStep ps = lawStep(s, deps_imposed, B, z);
    law.update(ps, state_n, state, r.sigma, &T);
    LAMINA_CHECK(r.sigma.allFinite(), "plane stress: the law's stress is not finite after ", it,
                 " iterations");
    r.residual = constrainedStress(s, B, r.sigma);
    const double scale = planeStressScale(r.sigma, maxC0, s.eps_n, ps.eps);
    if (r.residual <= tolerance * scale) {
      r.iterations = it;
      storeUnknowns(s, ps, z, r);
      break;
    }
    if (it == kPlaneStressMaxIterations)
      throw Error(detail::concat("plane stress: the out-of-plane stress did not vanish: residual ",
                                 r.residual, " Pa after ", it, " iterations (tolerance ", tolerance,
                                 " x ", scale, " Pa)"));
    VecZ<N> dz = (B.transpose() * T * B).partialPivLu().solve(B.transpose() * r.sigma);
    for (int halve = 0; std::abs(z[0] - dz[0]) > kMaxThicknessIncrement && halve < 60; ++halve)
      dz *= 0.5;
    z -= dz;
  }
  if (want_tangent)
    r.tangent = condensedTangent(T, B);
  return r;
}

} // namespace

PlaneStressResult planeStressUpdate(const ConstitutiveLaw& law, const PlaneStressStep& s,
                                    const double* state_n, double* state, bool want_tangent,
                                    double tolerance) {
  checkStep(s);
  LAMINA_CHECK(tolerance > 0 && std::isfinite(tolerance),
               "plane stress: the tolerance must be positive, got ", tolerance);
  switch (s.n_free) {
  case 0:
    return update<3>(law, s, state_n, state, want_tangent, tolerance);
  case 1:
    return update<4>(law, s, state_n, state, want_tangent, tolerance);
  case 2:
    return update<5>(law, s, state_n, state, want_tangent, tolerance);
  default:
    return update<6>(law, s, state_n, state, want_tangent, tolerance);
  }
}

} // namespace lamina::materials
