#pragma once
/// @file material.hpp
/// @brief One entry of the materials library: stiffness, density, provenance.

#include "materials/reduced_order.hpp"
#include "materials/stiffness.hpp"

#include <toml++/toml.h>

#include <array>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace lamina::materials {

/// One ply of a layup: a material, its angle about z and its thickness.
struct Ply {
  std::string material; ///< library or catalog name of the ply material
  double angle_deg = 0; ///< rotation about z, degrees, counter-clockwise from x
  double thickness = 0; ///< m, > 0
};

/// A material as the library stores it.
struct Material {
  std::string name;                ///< unique key in the library
  Stiffness C;                     ///< 6x6, lamina order, Pa
  double density = 0;              ///< kg/m^3, > 0
  /// "catalog", "homogenized", "layup", "constants" or "reduced-order"
  std::string kind = "catalog";
  std::optional<double> thickness; ///< total thickness (m), layups only
  std::vector<Ply> plies;          ///< the plies, layups only
  std::string side_file;           ///< optional HDF5 side file with large arrays
  /// fileChecksum() of the side file, set when the library writes it and
  /// checked where the side file is read
  std::string side_checksum;
  /// Reduced-order cells (kind "reduced-order"): the cell's phases, each
  /// with its law and density; the arrays are in the side file
  /// (reduced_order.hpp)
  std::vector<ReducedOrderPhase> phases;
  toml::table provenance;          ///< what made it (free-form, written verbatim)
  /// Micro-inertia (GVBO chapter eq. 35): zeta^2 D, the coefficient of the
  /// engineering strain acceleration in the stress, 6x6, lamina order, kg/m;
  /// symmetric positive semi-definite. Absent: no micro-inertia.
  std::optional<Matrix6> dispersion;
  /// Edge lengths of the unit cell that made the dispersion (m); present
  /// with it on homogenized entries.
  std::optional<Eigen::Vector3d> cell_size;
};

/// Throws lamina::Error naming @p name unless the dispersion @p D (kg/m) is
/// finite, symmetric and positive semi-definite.
void validateDispersion(const Matrix6& D, const std::string& name);

/// The characteristic lengths of micro-inertia, sqrt(zeta^2 D_II / rho) per
/// lamina component I (m): a plane wave whose strain is component I alone
/// (P waves along x: I = xx; S waves along x polarised in y: I = xy...)
/// follows omega^2 = c^2 k^2 / (1 + l_I^2 k^2). Zero without dispersion.
std::array<double, 6> dispersionLengths(const Material& m);

/// The kind of a reduced-order cell entry ("reduced-order").
inline constexpr const char* kReducedOrderKind = "reduced-order";

/// Throws lamina::Error naming the material unless C is symmetric positive
/// definite, the density is finite and positive and the thickness (if any)
/// is positive, the dispersion (if any) is finite, symmetric and positive
/// semi-definite and the cell size positive, a side_checksum comes with a
/// side_file, and phases are those of a reduced-order entry
/// (validateReducedOrderPhases) or absent. (A reduced-order entry's side
/// file and checksum are set when the library writes it, and required
/// where the library reads it.)
void validate(const Material& m);

/// Throws lamina::Error naming the entry @p name and the phase ("phases[i]
/// ('soft'): ...") unless there is at least one phase, every phase has a
/// unique non-empty name, a positive density and a valid law that is not
/// reduced-order itself.
void validateReducedOrderPhases(const std::vector<ReducedOrderPhase>& phases,
                                const std::string& name);

} // namespace lamina::materials
