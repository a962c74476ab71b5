#include "materials/symmetry.hpp"

#include <cmath>

namespace lamina::materials {

namespace {
bool invariant(const Stiffness& c, int axis, double degrees, double tol) {
  const Matrix6 d = c.rotated(axisRotationDegrees(axis, degrees)).matrix() - c.matrix();
  return d.cwiseAbs().maxCoeff() <= tol * c.matrix().cwiseAbs().maxCoeff();
}
} // namespace

Symmetry classify(const Stiffness& c, double tol) {
  const double generic = 35.26439; // degrees; not a multiple of any crystallographic angle
  const double quarter = 90, half = 180;
  bool ti[3];
  for (int a = 0; a < 3; ++a)
    ti[a] = invariant(c, a, generic, tol);
  if ((ti[0] && ti[1]) || (ti[1] && ti[2]) || (ti[0] && ti[2]))
    return {SymmetryClass::Isotropic, -1};
  if (invariant(c, 0, quarter, tol) && invariant(c, 1, quarter, tol) &&
      invariant(c, 2, quarter, tol))
    return {SymmetryClass::Cubic, -1};
  for (int a = 0; a < 3; ++a)
    if (ti[a])
      return {SymmetryClass::TransverselyIsotropic, a};
  bool twofold[3];
  for (int a = 0; a < 3; ++a)
    twofold[a] = invariant(c, a, half, tol);
  if (twofold[0] && twofold[1] && twofold[2])
    return {SymmetryClass::Orthotropic, -1};
  for (int a = 0; a < 3; ++a)
    if (twofold[a])
      return {SymmetryClass::Monoclinic, a};
  return {SymmetryClass::Triclinic, -1};
}

std::string toString(SymmetryClass cls) {
  return std::string(kSymmetryClassNames.name(cls));
}

} // namespace lamina::materials
