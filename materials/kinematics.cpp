#include "materials/kinematics.hpp"

#include "core/error.hpp"

namespace lamina::materials {

Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& F) {
  LAMINA_CHECK(F.determinant() > 0, "deformation gradient with det F <= 0");
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
