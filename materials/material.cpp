#include "materials/material.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <set>

namespace lamina::materials {

void validate(const Material& m) {
  core::checkName(m.name, "material name"); // the message shows it printably
  const ErrorContext ctx{"", 0, m.name};
  m.C.validate(m.name);
  if (!(m.density > 0) || !std::isfinite(m.density))
    throw Error("density must be positive and finite (kg/m^3), got " + core::formatShort(m.density),
                ctx);
  if (m.thickness && (!(*m.thickness > 0) || !std::isfinite(*m.thickness)))
    throw Error("thickness must be positive (m), got " + core::formatShort(*m.thickness), ctx);
  for (const Ply& p : m.plies)
    if (!(p.thickness > 0))
      throw Error("ply thickness must be positive (m)", ctx);
  if (m.dispersion)
    validateDispersion(*m.dispersion, m.name);
  if (m.cell_size && !(m.cell_size->minCoeff() > 0 && m.cell_size->allFinite()))
    throw Error("cell_size must be positive and finite (m)", ctx);
  if (!m.side_checksum.empty() && m.side_file.empty())
    throw Error("side_checksum without a side_file", ctx);
  if (m.kind == kReducedOrderKind)
    validateReducedOrderPhases(m.phases, m.name);
  else if (!m.phases.empty())
    throw Error("phases belong to entries of kind \"" + std::string(kReducedOrderKind) +
                    "\", not \"" + m.kind + "\"",
                ctx);
}

void validateReducedOrderPhases(const std::vector<ReducedOrderPhase>& phases,
                                const std::string& name) {
  const ErrorContext ctx{"", 0, name};
  if (phases.empty())
    throw Error("phases: a reduced-order entry needs at least one phase", ctx);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < phases.size(); ++i) {
    const ReducedOrderPhase& p = phases[i];
    const std::string where = "phases[" + std::to_string(i) + "] ('" + p.name + "'): ";
    if (p.name.empty())
      throw Error("phases[" + std::to_string(i) + "]: the phase name must not be empty", ctx);
    if (!seen.insert(p.name).second)
      throw Error(where + "two phases have this name", ctx);
    if (!(p.density > 0) || !std::isfinite(p.density))
      throw Error(where + "density must be positive and finite (kg/m^3)", ctx);
    try {
      p.law.C.validate("law");
      p.law.make(); // refuses a reduced-order law, checks the GVBO parameters
    } catch (const Error& e) {
      throw Error(where + e.message(), ctx);
    }
  }
}

void validateDispersion(const Matrix6& D, const std::string& name) {
  const ErrorContext ctx{"", 0, name};
  if (!D.allFinite())
    throw Error("dispersion has a non-finite entry", ctx);
  const double scale = D.cwiseAbs().maxCoeff();
  if ((D - D.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale)
    throw Error("dispersion must be symmetric (kg/m, lamina order)", ctx);
  // a Gram matrix: eigenvalues >= 0 up to round-off of its largest
  const double lmin = Eigen::SelfAdjointEigenSolver<Matrix6>(D).eigenvalues().minCoeff();
  if (lmin < -1e-10 * scale)
    throw Error("dispersion must be positive semi-definite (smallest eigenvalue " +
                    std::to_string(lmin) + " kg/m)",
                ctx);
}

std::array<double, 6> dispersionLengths(const Material& m) {
  std::array<double, 6> l{};
  if (m.dispersion)
    for (int i = 0; i < 6; ++i)
      l[static_cast<std::size_t>(i)] = std::sqrt(std::max(0.0, (*m.dispersion)(i, i)) / m.density);
  return l;
}

} // namespace lamina::materials
