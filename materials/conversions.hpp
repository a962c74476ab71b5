#pragma once
/// @file conversions.hpp
/// @brief The one place where lamina order meets every other 6x6 order.
///
/// Orders (all with engineering shear strain unless stated):
/// - lamina:  xx yy zz xy yz xz (membrane paper eq. (6))
/// - Voigt:   11 22 33 23 13 12 (standard)
/// - Mandel:  11 22 33 23 13 12 with shear rows and columns scaled by sqrt(2)
///            (tensorial shear, orthonormal basis: rotations are orthogonal)
/// - Abaqus / CalculiX: 11 22 33 12 13 23; the card lists the upper triangle
///            column by column: D1111 D1122 D2222 D1133 D2233 D3333 D1112 ...
/// - LS-DYNA: xx yy zz xy yz zx (= lamina order); *MAT_ANISOTROPIC_ELASTIC
///            lists the upper triangle column by column: C11 C12 C22 C13 ...

#include "materials/stiffness.hpp"

#include <array>
#include <utility>

namespace lamina::materials {

/// Lamina index of each standard Voigt position (V[k] = L[kVoigtFromLamina[k]]).
constexpr std::array<int, 6> kVoigtFromLamina{0, 1, 2, 4, 5, 3};
/// Lamina index of each Abaqus position (11 22 33 12 13 23).
constexpr std::array<int, 6> kAbaqusFromLamina{0, 1, 2, 3, 5, 4};

/// Lamina order -> standard Voigt order (11 22 33 23 13 12).
Matrix6 toVoigt(const Matrix6& lamina);
/// Standard Voigt order -> lamina order.
Matrix6 fromVoigt(const Matrix6& voigt);
/// Lamina order -> Mandel form (Voigt order, sqrt(2) on shear).
Matrix6 toMandel(const Matrix6& lamina);
/// Mandel form -> lamina order.
Matrix6 fromMandel(const Matrix6& mandel);
/// Lamina order -> Abaqus order (11 22 33 12 13 23).
Matrix6 toAbaqus(const Matrix6& lamina);
/// Abaqus order -> lamina order.
Matrix6 fromAbaqus(const Matrix6& abaqus);

/// The 21 values of an Abaqus/CalculiX anisotropic card, in card order
/// (upper triangle of the Abaqus-order matrix, column by column).
std::array<double, 21> abaqusCardValues(const Matrix6& lamina);
/// Inverse of abaqusCardValues().
Matrix6 fromAbaqusCardValues(const std::array<double, 21>& values);
/// The 21 values of an LS-DYNA *MAT_ANISOTROPIC_ELASTIC card, in card order
/// (upper triangle of the lamina-order matrix, column by column).
std::array<double, 21> lsdynaCardValues(const Matrix6& lamina);
/// Inverse of lsdynaCardValues().
Matrix6 fromLsdynaCardValues(const std::array<double, 21>& values);

/// 6x6 orthogonal matrix acting on Mandel vectors for the 3x3 rotation @p R:
/// (R eps R^T)_M = Q eps_M.
Matrix6 mandelRotation(const Eigen::Matrix3d& R);

/// Symmetric 3x3 strain tensor -> lamina-order engineering strain vector.
Eigen::Matrix<double, 6, 1> strainToLamina(const Eigen::Matrix3d& eps);
/// Lamina-order engineering strain vector -> symmetric 3x3 strain tensor.
Eigen::Matrix3d strainFromLamina(const Eigen::Matrix<double, 6, 1>& v);

} // namespace lamina::materials
