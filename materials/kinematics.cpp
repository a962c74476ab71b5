#include "materials/kinematics.hpp"

#include "core/error.hpp"

namespace lamina::materials {

namespace {

/// @return X^-T = cof(X) / det X: its columns are the cross products of X's
/// columns (the cofactor matrix), @p det receives det X
Eigen::Matrix3d inverseTranspose(const Eigen::Matrix3d& X, double& det) {
  Eigen::Matrix3d C;
  C.col(0) = X.col(1).cross(X.col(2));
  C.col(1) = X.col(2).cross(X.col(0));
  C.col(2) = X.col(0).cross(X.col(1));
  det = X.col(0).dot(C.col(0));
  return C * (1 / det);
}

} // namespace

Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& F) {
  LAMINA_CHECK(F.determinant() > 0, "deformation gradient with det F <= 0");
  // Newton's iteration for the orthogonal polar factor (Higham 1986),
  // X <- (g X + X^-T / g) / 2 with the Frobenius-norm scaling g while far
  // from converged: quadratic near R, a handful of iterations for the
  // stretches of a step (every X keeps det > 0, so the limit is a rotation).
  Eigen::Matrix3d X = F;
  for (int it = 0; it < 40; ++it) {
    double det = 0;
    const Eigen::Matrix3d Xit = inverseTranspose(X, det);
    if (!(det > 0)) // det > 0 holds in exact arithmetic; near a singular F, the SVD
      break;
    double g = 1;
    // scaling only far from R: near it, it would only add round-off
    if ((Xit - X).squaredNorm() > 1e-4)
      g = std::sqrt(Xit.norm() / X.norm());
    const Eigen::Matrix3d next = 0.5 * (g * X + Xit / g);
    const double step2 = (next - X).squaredNorm();
    X = next;
    // the correction is quadratic in the distance to R: once it is below
    // 1e-9, the next one lies below round-off
    if (step2 <= 1e-18) {
      const Eigen::Matrix3d last = inverseTranspose(X, det);
      if (!(det > 0))
        break;
      return 0.5 * (X + last);
    }
  }
  // not converged (a stretch far beyond any step's) or a determinant that
  // round-off turned: the SVD
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

Eigen::Matrix3d toMatrix(const Vector6& s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return m;
}

Vector6 fromMatrix(const Eigen::Matrix3d& m) {
  Vector6 s;
  s << m(0, 0), m(1, 1), m(2, 2), 0.5 * (m(0, 1) + m(1, 0)), 0.5 * (m(1, 2) + m(2, 1)),
      0.5 * (m(0, 2) + m(2, 0));
  return s;
}

Vector6 rotateTensor(const Eigen::Matrix3d& R, const Vector6& s) {
  return fromMatrix(R * toMatrix(s) * R.transpose());
}

Vector6 smallStrain(const Eigen::Matrix3d& F) {
  Vector6 e = fromMatrix(F - Eigen::Matrix3d::Identity());
  e.tail<3>() *= 2; // engineering shear
  return e;
}

Vector6 rotationFreeIncrement(const Eigen::Matrix3d& F_n, const Eigen::Matrix3d& F) {
  LAMINA_CHECK(F_n.determinant() > 0 && F.determinant() > 0,
               "deformation gradient with det F <= 0");
  const Eigen::Matrix3d Fm = 0.5 * (F_n + F);
  const Eigen::Matrix3d Ldt = (F - F_n) * Fm.inverse();
  const Eigen::Matrix3d Dm = 0.5 * (Ldt + Ldt.transpose());
  const Eigen::Matrix3d Rm = polarRotation(Fm);
  Vector6 deps = fromMatrix(Rm.transpose() * Dm * Rm);
  deps.tail<3>() *= 2; // engineering shear
  return deps;
}

FiniteIncrement finiteIncrement(const Eigen::Matrix3d& F_n, const Eigen::Matrix3d& F) {
  FiniteIncrement inc;
  inc.J_n = F_n.determinant();
  inc.J = F.determinant();
  inc.deps = rotationFreeIncrement(F_n, F);
  inc.R = polarRotation(F);
  return inc;
}

} // namespace lamina::materials
