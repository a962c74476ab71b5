#pragma once
/// @file reduced_order.hpp
/// @brief The data of a reduced-order unit cell (polyurea chapter, section
/// 4.2, eqs. 22-34; micro-inertia eqs. 37-40): what `homogenize
/// --reduced-order` computes once on a cell's voxels and what the
/// reduced-order law (reduced_order_law.hpp) needs at every material point.
///
/// The cell is split into n partitions Theta^(alpha) (eq. 29), each inside
/// one phase. With the reference (instantaneous, J = 1) stiffness L0 of
/// every phase, the influence functions are
/// - H_k: the periodic displacement of unit macro strain k (k = 0..5,
///   lamina order, engineering shear), the six load cases of the linear
///   homogenizer;
/// - S^(alpha)_J: the periodic displacement of a unit eigenstrain J
///   (engineering) piecewise constant on partition alpha (eqs. 29, 31):
///   div L0 (grad S - e_J N^(alpha)) = 0, zero macro strain.
/// Averaging eq. 32 over partition beta gives the reduced system
///     d eps^(beta) = A^(beta) d eps^c + sum_alpha P^(beta alpha) d mu^(alpha)
/// with A^(beta) = <I + grad H>_beta (column k: the mean strain of partition
/// beta under unit macro strain k) and P^(beta alpha) = <grad S^(alpha)>_beta
/// (column J: the mean strain of partition beta under unit eigenstrain J on
/// alpha). Every matrix is 6x6 in lamina order, strains engineering.
///
/// Micro-inertia (eq. 40), all in kg/m like Material::dispersion (the grid
/// in metres): R^(alpha beta)_IJ = rho_c <S^(alpha)_I . S^(beta)_J> and
/// Q^(alpha)_IJ = rho_c <h_I . S^(alpha)_J>, h the dispersion displacement
/// of eq. 39 (homogenize/dispersion.hpp), with the same cell average (the
/// trilinear interpolant of the nodal fields) and zero-mean fields.
///
/// Invariants (validate()): n >= 1; every partition has a phase, a fraction
/// in (0, 1] and the fractions sum to 1 (1e-12); all numbers finite; the
/// sizes match n.
#include "core/checksum.hpp"
#include "core/enum_names.hpp"
#include "materials/law_spec.hpp"
#include "materials/stiffness.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lamina::materials {

/// How the law couples the partitions (reduced_order_law.hpp).
enum class ReducedOrderScheme {
  /// transformation-field analysis, the chapter's eqs. 22-34: eigenstrains
  /// through the influence functions A, P of each phase's reference
  /// stiffness; exact for elastic phases with any partitioning
  Transformation,
  /// clustering analysis (Liu, Bessa and Liu 2016): the partitions'
  /// Lippmann-Schwinger equation in an isotropic reference medium that
  /// follows the softest phase's secant shear modulus, through Ga, Gb
  Clustering
};

/// The names of ReducedOrderScheme on the command line (`homogenize
/// --scheme`) and in side files.
inline constexpr auto kReducedOrderSchemeNames = core::enumNames<ReducedOrderScheme>(
    {{"tfa", ReducedOrderScheme::Transformation}, {"clustering", ReducedOrderScheme::Clustering}});

/// @return "tfa" or "clustering" (kReducedOrderSchemeNames)
const char* toString(ReducedOrderScheme scheme);

/// One phase of the cell: its name in the cell file and its law.
struct ReducedOrderPhase {
  std::string name;   ///< phase name of the cell file ("soft", "hard")
  LawSpec law;        ///< the law (its C at J = 1 is the reference stiffness L0)
  double density = 0; ///< kg/m^3
};

/// The reduced-order model of one cell.
struct ReducedOrderModel {
  std::vector<ReducedOrderPhase> phases;     ///< the cell's phases
  std::vector<std::int32_t> partition_phase; ///< n: phase index of partition alpha
  std::vector<double> fraction;              ///< n: volume fraction c_alpha (sum 1)
  std::vector<Matrix6> A;                    ///< n: strain concentration A^(alpha)
  /// n * n: P[beta * n + alpha] = P^(beta alpha), mean strain of beta under
  /// unit eigenstrains on alpha
  std::vector<Matrix6> P;
  Eigen::MatrixXd R; ///< 6n x 6n: block (alpha, beta) is R^(alpha beta) (kg/m)
  Eigen::MatrixXd Q; ///< 6 x 6n: block alpha is Q^(alpha) (kg/m)
  /// how the law couples the partitions
  ReducedOrderScheme scheme = ReducedOrderScheme::Transformation;
  /// clustering only (else empty), n * n each: the two
  /// fixed parts of the interaction tensors, G^(IJ) = (Ga - beta Gb) / mu0
  /// of the reference medium (homogenize/cluster_interaction.hpp)
  std::vector<Matrix6> Ga, Gb;
  Matrix6 D_lin = Matrix6::Zero(); ///< zeta^2 D_lin of eq. 38 (kg/m)
  Matrix6 C = Matrix6::Zero();     ///< effective reference stiffness of the cell (Pa)
  double density = 0;              ///< mean density rho_c (kg/m^3)

  /// @return the number of partitions n
  int partitions() const { return static_cast<int>(fraction.size()); }
  /// @return the number of partitions of each phase
  std::vector<int> partitionsPerPhase() const;
  /// @return sym(sum_alpha c_alpha L0 A^(alpha)) with @p L0 the reference
  /// stiffness of each phase: the cell's stiffness while every phase is
  /// elastic (what C holds)
  Matrix6 referenceStiffness(const std::vector<Stiffness>& L0) const;
  /// Throws lamina::Error prefixed by @p where unless the invariants hold.
  void validate(const std::string& where) const;
};

/// Writes the arrays of @p m (everything but the phases' laws and names) to
/// the HDF5 file @p path: datasets /partition_phase (n), /fraction (n),
/// /A (n x 6 x 6), /P (n x n x 6 x 6), /R (6n x 6n), /Q (6 x 6n), /D_lin
/// (6 x 6), /C (6 x 6), /density (1), and the attribute "format" =
/// "lamina-reduced-order-cell 1" on "/". A clustering cell
/// also has /Ga and /Gb (n x n x 6 x 6) and the attribute "scheme" = "clustering",
/// and is format "lamina-reduced-order-cell 2" (a reader of format 1 alone
/// refuses it rather than run it as the other scheme).
void writeReducedOrderArrays(const std::filesystem::path& path, const ReducedOrderModel& m);

/// Reads the arrays written by writeReducedOrderArrays into @p m (whose
/// phases are already set: every partition_phase must name one of them).
/// Throws lamina::Error naming @p path and the dataset for a missing or
/// malformed dataset, or a model that fails validate().
void readReducedOrderArrays(const std::filesystem::path& path, ReducedOrderModel& m);

/// The checksum the library keeps of side files (core/checksum.hpp).
using core::fileChecksum;

} // namespace lamina::materials
