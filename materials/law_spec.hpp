#pragma once
/// @file law_spec.hpp
/// @brief A constitutive law as an input file gives it (catalog entry, cell
/// phase): its kind, its elastic constants and, for GVBO, its parameters;
/// read by one function for every file.
///
/// Keys by `law` (SI units): `isotropic`: E, nu; `transversely-isotropic`:
/// E1, E2, G12, nu12, nu23 (axis x); `anisotropic`: C (6 rows of 6, lamina
/// order); `gvbo`: E, nu (= E0, nu0) and a `gvbo` sub-table of Et, p, a1, a2,
/// a3, k1, k2, k3, k4, Em, A0, Ac, Af (polyurea chapter, Table 1); `fabric`:
/// E_warp or warp_curve, E_fill or fill_curve, G12, optional nu12 = 0
/// (fabric_law.hpp; a curve file is relative to the file that names it); `void`
/// (a cell's pore): no keys, C = 0 (only where the caller allows it).

#include "materials/fabric_law.hpp"
#include "materials/gvbo.hpp"
#include "materials/law.hpp"
#include "materials/stiffness.hpp"

#include <iosfwd>
#include <optional>

namespace lamina::core {
class TableReader;
}

namespace lamina::materials {

/// A law read from a file.
struct LawSpec {
  LawKind kind = LawKind::Isotropic; ///< which law
  /// elastic stiffness (gvbo: at J = 1, from E0, nu0; fabric: its
  /// instantaneous stiffness at J = 1, FabricLaw::elasticStiffness)
  Stiffness C;
  std::optional<GvboParameters> gvbo;     ///< set for LawKind::Gvbo
  std::optional<FabricParameters> fabric; ///< set for LawKind::Fabric
  /// @return the law object: LinearElasticLaw(kind, C), GvboLaw(*gvbo) or FabricLaw(*fabric)
  LawPtr make() const;
};

/// Whether a reader takes `law = "void"` (a pore: zero stiffness).
enum class VoidLaw {
  Refused, ///< catalog entries, case sections, library entries: a material has stiffness
  Allowed  ///< a cell's [[phases]] (the linear homogenization handles pores)
};

/// Reads the law of @p t from key `law` and the keys of that law. Throws
/// lamina::Error naming the file and key for an unknown law, `law =
/// "reduced-order"` (a library entry referred to by its name, not a law with
/// keys), `law = "void"` unless @p void_law allows it or with elastic
/// constants, a missing key, E <= 0, nu outside (-1, 0.5), or a C that is
/// not symmetric positive definite.
LawSpec readLawSpec(const core::TableReader& t, VoidLaw void_law = VoidLaw::Refused);

/// Writes @p law as TOML lines that readLawSpec reads back exactly: a gvbo
/// law as `law = "gvbo"`, E, nu and an inline `gvbo` table of its 13
/// parameters; a linear law as `law = "anisotropic"` and its C (a linear
/// law is its C; 17 significant digits, bit for bit). A fabric law (whose
/// curves live in files) is not written: an internal error.
void writeLawSpec(std::ostream& os, const LawSpec& law);

/// Reads the keys of law @p kind from @p t (as readLawSpec, `law` already
/// known; LawKind::Void: checks that @p t gives no elastic constants).
LawSpec readLawConstants(const core::TableReader& t, LawKind kind);

/// Stiffness of a transversely isotropic material with axis x from its
/// engineering constants (lamina order; G23 = E2 / (2 (1 + nu23))).
Stiffness transverselyIsotropic(double E1, double E2, double G12, double nu12, double nu23);

} // namespace lamina::materials
