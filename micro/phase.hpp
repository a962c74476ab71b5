#pragma once
/// @file phase.hpp
/// @brief One material phase of a unit cell: its law, stiffness and density.
///
/// A phase is read from a `[[phases]]` table of a cell file (see
/// docs/homogenize.md). Laws (materials::readLawSpec): "isotropic" (E, nu),
/// "transversely-isotropic", "anisotropic" (C, 6x6, lamina order, Pa) and
/// "gvbo" (the polyurea chapter's law; for a linear
/// homogenization it contributes its instantaneous isotropic moduli at a
/// matrix state J, eqs. 13-16, never below the initial moduli); "void" is a
/// pore (zero stiffness and density, no other keys; linear homogenization
/// only, docs/homogenize-solver.md "Pores"). A phase can
/// instead name a catalog entry (`catalog = "NAME"`), which supplies law,
/// parameters and density.

#include "materials/catalog.hpp"
#include "materials/gvbo.hpp"
#include "materials/law.hpp"
#include "materials/law_spec.hpp"
#include "materials/stiffness.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lamina::core {
class TableReader;
}

namespace lamina::micro {

/// A phase of a unit cell.
struct Phase {
  std::string name;                                       ///< unique name within the cell
  materials::LawKind law = materials::LawKind::Isotropic; ///< which law
  std::string source;                                     ///< "catalog:NAME" or "inline"
  materials::Stiffness C; ///< elastic stiffness (gvbo: at J = 1), lamina order, Pa
  double density = 0;     ///< kg/m^3, > 0 (0 for a void phase)
  std::optional<materials::GvboParameters> gvbo; ///< set for law "gvbo"
  std::vector<double> J;                         ///< gvbo states to homogenize at (empty: J = 1)
  /// The law object of the phase (shared by all its voxels): GvboLaw or
  /// LinearElasticLaw(C). Linear solvers keep using C (or stiffnessAt).
  materials::LawPtr model;
  std::optional<std::int32_t> id; ///< image value the phase owns (`id = K`; image cells)

  /// Stiffness of the phase at matrix state @p J (lamina order, Pa). For a
  /// gvbo phase: isotropic from gvboModuli(J) (eqs. 13-16 of the chapter);
  /// for other laws @p J is ignored and C is returned.
  materials::Stiffness stiffnessAt(double J) const;
  /// @return the law as its file gave it (kind, C, GVBO parameters): the
  /// spec model was made from
  materials::LawSpec lawSpec() const { return {law, C, gvbo, std::nullopt}; }
  /// @return whether the phase is a pore (law "void": C = 0, density 0)
  bool isVoid() const { return law == materials::LawKind::Void; }
  /// @return whether every rotation leaves the phase's stiffness as it is:
  /// law isotropic or gvbo (isotropic at every J), or a C classified
  /// isotropic to 1e-12 of max |C| (round-off of a C entered isotropic)
  bool isotropic() const;
};

/// Supplies catalog entries on demand (the catalog file is read only when a
/// phase names one).
using CatalogProvider = std::function<const materials::Catalog&()>;

/// Reads one `[[phases]]` table. Throws lamina::Error naming the file and key
/// on a missing, unknown or invalid value (E <= 0, nu outside (-1, 0.5), C not
/// symmetric positive definite, J <= 0, J given for a non-gvbo phase,
/// density or elastic constants given for a void phase...).
Phase readPhase(const core::TableReader& t, const CatalogProvider& catalog);

} // namespace lamina::micro
