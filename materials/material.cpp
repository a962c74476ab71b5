#include "materials/material.hpp"

#include "core/error.hpp"

#include <cmath>

namespace lamina::materials {

void validate(const Material& m) {
  const ErrorContext ctx{"", 0, m.name};
  if (m.name.empty())
    throw Error("material name is empty");
  m.C.validate(m.name);
  if (!(m.density > 0) || !std::isfinite(m.density))
    throw Error("density must be positive and finite (kg/m^3), got " + std::to_string(m.density),
                ctx);
  if (m.thickness && (!(*m.thickness > 0) || !std::isfinite(*m.thickness)))
    throw Error("thickness must be positive (m), got " + std::to_string(*m.thickness), ctx);
  for (const Ply& p : m.plies)
    if (!(p.thickness > 0))
      throw Error("ply thickness must be positive (m)", ctx);
}

} // namespace lamina::materials
