// The polar rotation of F = R U (materials/kinematics.hpp) against factors
// built exactly: R from an angle and an axis, U symmetric positive definite
// from chosen principal stretches and axes. The polar factors are unique for
// det F > 0, so the R of the product must come back.
#include "materials/kinematics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace mat = lamina::materials;

namespace {

/// U = Q diag(l) Q^T with Q a rotation about @p axis by @p angle.
Eigen::Matrix3d stretch(const Eigen::Vector3d& l, double angle, const Eigen::Vector3d& axis) {
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return Q * l.asDiagonal() * Q.transpose();
}

} // namespace

// From a near-identity step (the membrane's increments) to a stretch ratio of
// 1e4 (far beyond any step, where the iteration needs its scaling): the
// rotation to 1e-13, an orthogonality and round-off bound for a product of a
// few 3 x 3 matrices whose condition number grows with the stretch ratio.
TEST(PolarRotation, RecoversTheRotationOfAProductRU) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -1.0, 0.4).normalized()).toRotationMatrix();
  const Eigen::Vector3d axis(1.0, 2.0, -0.5);
  for (const Eigen::Vector3d& l :
       {Eigen::Vector3d(1.0, 1.0, 1.0), Eigen::Vector3d(1.0 + 1e-7, 1.0 - 2e-7, 1.0),
        Eigen::Vector3d(1.2, 0.9, 0.7), Eigen::Vector3d(3.0, 0.5, 1.0),
        Eigen::Vector3d(100.0, 0.1, 1.0), Eigen::Vector3d(1e2, 1e-2, 1.0)}) {
    const Eigen::Matrix3d F = R * stretch(l, 0.7, axis);
    const Eigen::Matrix3d Rp = mat::polarRotation(F);
    EXPECT_LT((Rp - R).cwiseAbs().maxCoeff(), 1e-13) << "stretches " << l.transpose();
    EXPECT_LT((Rp.transpose() * Rp - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_GT(Rp.determinant(), 0);
  }
}

// A rotation is its own polar factor, to round-off.
TEST(PolarRotation, OfARotationIsItself) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(-0.4, Eigen::Vector3d(1.0, 1.0, 1.0).normalized()).toRotationMatrix();
  EXPECT_LT((mat::polarRotation(R) - R).cwiseAbs().maxCoeff(), 1e-15);
}
