#pragma once
/// @file stiffness.hpp
/// @brief The 6x6 elastic stiffness in lamina order.
///
/// Lamina order (DESIGN.md, membrane paper eq. (6)): stress
/// [sxx, syy, szz, sxy, syz, sxz], engineering shear strain
/// [exx, eyy, ezz, gxy, gyz, gxz] (gamma = 2 eps). Units: Pa.
/// Conversions to other orders live in conversions.hpp, and only there.

#include <Eigen/Dense>

#include <array>
#include <iosfwd>
#include <string>
#include <string_view>

namespace lamina::core {
class TableReader;
}

namespace lamina::materials {

/// 6x6 matrix in lamina order.
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Engineering constants of a stiffness (from its compliance).
struct EngineeringConstants {
  double E1, E2, E3;       ///< Young's moduli along x, y, z (Pa)
  double G12, G23, G13;    ///< shear moduli xy, yz, xz (Pa)
  double nu12, nu13, nu23; ///< nu_ij = -S_ji / S_ii: lateral strain j per axial strain i
  double nu21, nu31, nu32; ///< the reciprocal Poisson ratios
};

/// Tensor index pair (i, j) of each lamina-order component.
constexpr std::array<std::pair<int, int>, 6> kLaminaPairs{
    {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}}};

/// A symmetric 6x6 elastic stiffness in lamina order (Pa).
class Stiffness {
public:
  /// Zero stiffness (not valid for use; fill it first).
  Stiffness() : c_(Matrix6::Zero()) {}
  /// Wraps @p c (lamina order, Pa); no check, call validate() on user input.
  explicit Stiffness(const Matrix6& c) : c_(c) {}

  /// Isotropic stiffness from Young's modulus @p E (Pa) and Poisson ratio @p nu
  /// (membrane paper eq. (16)). Requires E > 0 and -1 < nu < 0.5.
  static Stiffness isotropic(double E, double nu);
  /// Isotropic stiffness from the Lame constants (Pa); requires mu > 0 and
  /// 3 lambda + 2 mu > 0.
  static Stiffness fromLame(double lambda, double mu);
  /// From the 21 constants of the upper triangle, row by row, lamina order:
  /// C11 C12 C13 C14 C15 C16 C22 C23 ... C56 C66 (1-based, Pa).
  static Stiffness fromUpperTriangle(const std::array<double, 21>& c);
  /// @return the 21 constants of the upper triangle, row by row.
  std::array<double, 21> upperTriangle() const;

  /// @return the matrix (lamina order, Pa)
  const Matrix6& matrix() const { return c_; }
  /// @return entry (i, j), 0-based, lamina order
  double operator()(int i, int j) const { return c_(i, j); }

  /// Throws lamina::Error naming @p name unless the matrix is finite,
  /// symmetric (to 1e-10 relative) and positive definite (smallest
  /// eigenvalue > 1e-12 of the largest).
  void validate(const std::string& name) const;
  /// @return whether validate() would accept the matrix (no exception: for
  /// callers that sort stiffnesses, e.g. a pore's C = 0 from the others)
  bool valid() const;
  /// @return the smallest eigenvalue of the symmetric part (Pa)
  double smallestEigenvalue() const;
  /// @return max |C - C^T| / max |C|
  double asymmetry() const;
  /// @return the symmetric part (C + C^T)/2
  Stiffness symmetrized() const;

  /// @return the compliance S = C^-1 (lamina order, engineering shear, 1/Pa)
  Matrix6 compliance() const;
  /// @return E_i, G_ij, nu_ij from the compliance
  EngineeringConstants engineering() const;

  /// Rotates the tensor: C'_ijkl = R_ip R_jq R_kr R_ls C_pqrs, with @p R a
  /// proper or improper orthogonal 3x3 matrix (columns: new axes in old frame
  /// transposed; i.e. x' = R x maps material vectors).
  Stiffness rotated(const Eigen::Matrix3d& R) const;
  /// Rotation by @p radians about z (counter-clockwise seen from +z).
  Stiffness rotatedAboutZ(double radians) const;
  /// Rotation by @p radians about x.
  Stiffness rotatedAboutX(double radians) const;
  /// Rotation by @p radians about y.
  Stiffness rotatedAboutY(double radians) const;

private:
  Matrix6 c_;
};

/// Reads key @p key of @p t as 6 rows of 6 numbers (lamina order, unit
/// @p unit named in the message): the one reader of a 6x6 from TOML
/// (catalog, library, cells, cases). Throws lamina::Error naming the file
/// and key unless it has that shape; the caller validates the values
/// (Stiffness::validate).
Matrix6 readMatrix6(const core::TableReader& t, std::string_view key,
                    const std::string& unit = "Pa");

/// Writes @p c as TOML key @p key: 6 rows of 6 numbers with 17 significant
/// digits (read back bit for bit by readMatrix6), one row per line.
void writeMatrix6(std::ostream& os, std::string_view key, const Matrix6& c);

/// Rotation matrix of @p radians about the unit axis (x=0, y=1, z=2).
Eigen::Matrix3d axisRotation(int axis, double radians);
/// Rotation matrix of @p degrees about the unit axis (x=0, y=1, z=2), exact
/// (entries 0, 1, -1) for multiples of 90 degrees.
Eigen::Matrix3d axisRotationDegrees(int axis, double degrees);

/// Voigt average bulk modulus K_V (Pa).
double voigtBulk(const Stiffness& c);
/// Voigt average shear modulus G_V (Pa).
double voigtShear(const Stiffness& c);
/// Reuss average bulk modulus K_R (Pa).
double reussBulk(const Stiffness& c);
/// Reuss average shear modulus G_R (Pa).
double reussShear(const Stiffness& c);
/// Both Reuss moduli from one inversion of @p c (as reussBulk and reussShear).
/// @param bulk Reuss bulk modulus on exit (Pa)
/// @param shear Reuss shear modulus on exit (Pa)
void reussModuli(const Stiffness& c, double& bulk, double& shear);
/// Universal anisotropy index A^U = 5 G_V/G_R + K_V/K_R - 6 (Ranganathan and
/// Ostoja-Starzewski 2008): zero for an isotropic tensor, positive otherwise.
double anisotropyIndex(const Stiffness& c);

} // namespace lamina::materials
