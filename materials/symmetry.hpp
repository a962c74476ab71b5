#pragma once
/// @file symmetry.hpp
/// @brief Symmetry class of a stiffness in its own axes.
///
/// The class is detected by invariance under rotations about the coordinate
/// axes x, y, z (the material is assumed to be given in axes that align with
/// its symmetry elements, as catalog, homogenized and layup entries are):
/// - isotropic: invariant under generic rotations about two axes;
/// - cubic: invariant under 90 degree rotations about x, y and z;
/// - transversely isotropic: invariant under a generic rotation about one axis;
/// - orthotropic: invariant under 180 degree rotations about x, y and z;
/// - monoclinic: invariant under a 180 degree rotation about one axis;
/// - triclinic: none of these.
/// Invariance means max |C' - C| <= tol * max |C|.

#include "core/enum_names.hpp"
#include "materials/stiffness.hpp"

#include <string>

namespace lamina::materials {

/// The symmetry classes, from highest to lowest.
enum class SymmetryClass {
  Isotropic,
  Cubic,
  TransverselyIsotropic,
  Orthotropic,
  Monoclinic,
  Triclinic
};

/// Result of classify(): the class and, where it has one, the axis (0=x,1=y,2=z)
/// of transverse isotropy or of the monoclinic two-fold axis (-1 otherwise).
struct Symmetry {
  SymmetryClass cls; ///< the class
  int axis = -1;     ///< axis of transverse isotropy or two-fold axis (0=x, 1=y, 2=z), -1 if none
};

/// Detects the symmetry class of @p c with relative tolerance @p tol.
Symmetry classify(const Stiffness& c, double tol = 1e-6);

/// The printed names of SymmetryClass (summaries, provenance, JSON).
inline constexpr auto kSymmetryClassNames = core::enumNames<SymmetryClass>(
    {{"isotropic", SymmetryClass::Isotropic},
     {"cubic", SymmetryClass::Cubic},
     {"transversely isotropic", SymmetryClass::TransverselyIsotropic},
     {"orthotropic", SymmetryClass::Orthotropic},
     {"monoclinic", SymmetryClass::Monoclinic},
     {"triclinic", SymmetryClass::Triclinic}});

/// @return "isotropic", "cubic", "transversely isotropic", "orthotropic",
/// "monoclinic" or "triclinic"
std::string toString(SymmetryClass cls);

} // namespace lamina::materials
