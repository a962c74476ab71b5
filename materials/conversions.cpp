#include "materials/conversions.hpp"

#include <cmath>

namespace lamina::materials {

namespace {
Matrix6 permute(const Matrix6& m, const std::array<int, 6>& from) {
  Matrix6 out;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      out(i, j) = m(from[static_cast<std::size_t>(i)], from[static_cast<std::size_t>(j)]);
  return out;
}
Matrix6 unpermute(const Matrix6& m, const std::array<int, 6>& from) {
  Matrix6 out;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      out(from[static_cast<std::size_t>(i)], from[static_cast<std::size_t>(j)]) = m(i, j);
  return out;
}
const Eigen::Matrix<double, 6, 1> kMandelScale =
    (Eigen::Matrix<double, 6, 1>() << 1, 1, 1, std::sqrt(2.0), std::sqrt(2.0), std::sqrt(2.0))
        .finished();

// Upper triangle column by column: (0,0) (0,1) (1,1) (0,2) (1,2) (2,2) ...
std::array<double, 21> upperByColumns(const Matrix6& m) {
  std::array<double, 21> v{};
  std::size_t k = 0;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i <= j; ++i)
      v[k++] = m(i, j);
  return v;
}
Matrix6 fromUpperByColumns(const std::array<double, 21>& v) {
  Matrix6 m;
  std::size_t k = 0;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i <= j; ++i) {
      m(i, j) = v[k++];
      m(j, i) = m(i, j);
    }
  return m;
}
} // namespace

Matrix6 toVoigt(const Matrix6& l) {
  return permute(l, kVoigtFromLamina);
}
Matrix6 fromVoigt(const Matrix6& v) {
  return unpermute(v, kVoigtFromLamina);
}
Matrix6 toMandel(const Matrix6& l) {
  return kMandelScale.asDiagonal() * toVoigt(l) * kMandelScale.asDiagonal();
}
Matrix6 fromMandel(const Matrix6& m) {
  return fromVoigt(kMandelScale.cwiseInverse().asDiagonal() * m *
                   kMandelScale.cwiseInverse().asDiagonal());
}
Matrix6 toAbaqus(const Matrix6& l) {
  return permute(l, kAbaqusFromLamina);
}
Matrix6 fromAbaqus(const Matrix6& a) {
  return unpermute(a, kAbaqusFromLamina);
}

std::array<double, 21> abaqusCardValues(const Matrix6& l) {
  return upperByColumns(toAbaqus(l));
}
Matrix6 fromAbaqusCardValues(const std::array<double, 21>& v) {
  return fromAbaqus(fromUpperByColumns(v));
}
std::array<double, 21> lsdynaCardValues(const Matrix6& l) {
  return upperByColumns(l);
}
Matrix6 fromLsdynaCardValues(const std::array<double, 21>& v) {
  return fromUpperByColumns(v);
}

Matrix6 mandelRotation(const Eigen::Matrix3d& R) {
  // Orthonormal basis of symmetric tensors in Mandel (Voigt) order.
  static const std::array<std::pair<int, int>, 6> voigtPairs{
      {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  std::array<Eigen::Matrix3d, 6> basis;
  for (std::size_t a = 0; a < 6; ++a) {
    Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
    const auto [i, j] = voigtPairs[a];
    if (i == j) {
      e(i, i) = 1;
    } else {
      e(i, j) = e(j, i) = 1 / std::sqrt(2.0);
    }
    basis[a] = e;
  }
  Matrix6 q;
  for (std::size_t b = 0; b < 6; ++b) {
    const Eigen::Matrix3d rotated = R * basis[b] * R.transpose();
    for (std::size_t a = 0; a < 6; ++a)
      q(static_cast<int>(a), static_cast<int>(b)) = (basis[a].array() * rotated.array()).sum();
  }
  return q;
}

Eigen::Matrix<double, 6, 1> strainToLamina(const Eigen::Matrix3d& e) {
  Eigen::Matrix<double, 6, 1> v;
  v << e(0, 0), e(1, 1), e(2, 2), 2 * e(0, 1), 2 * e(1, 2), 2 * e(0, 2);
  return v;
}

Eigen::Matrix3d strainFromLamina(const Eigen::Matrix<double, 6, 1>& v) {
  Eigen::Matrix3d e;
  e << v(0), v(3) / 2, v(5) / 2, v(3) / 2, v(1), v(4) / 2, v(5) / 2, v(4) / 2, v(2);
  return e;
}

} // namespace lamina::materials
