#include "homogenize/macro_history.hpp"

#include "core/error.hpp"

#include <cmath>

namespace lamina::homogenize {

int MacroHistory::stressComponents() const {
  int m = 0;
  for (bool s : stress_controlled)
    m += s ? 1 : 0;
  return m;
}

MacroHistory pathHistory(materials::DrivePath path, double rate, double to, int steps,
                         bool unload) {
  materials::checkRate(rate, "rate");
  materials::checkFinalStrain(path, to, "final strain");
  LAMINA_CHECK(steps >= 1, "at least one step is needed");
  MacroHistory h;
  int driven = 0;
  double sign = 1;
  switch (path) {
  case materials::DrivePath::UniaxialStrain:
    break;
  case materials::DrivePath::Confined:
    sign = -1;
    break;
  case materials::DrivePath::Shear:
    driven = 3;
    break;
  case materials::DrivePath::UniaxialStress:
    for (int i = 1; i < 6; ++i)
      h.stress_controlled[static_cast<std::size_t>(i)] = true;
    break;
  case materials::DrivePath::BiaxialStress:
    for (int i = 2; i < 6; ++i)
      h.stress_controlled[static_cast<std::size_t>(i)] = true;
    break;
  }
  const bool biaxial = path == materials::DrivePath::BiaxialStress;
  const double dt = to / rate / steps;
  const int total = unload ? 2 * steps : steps;
  for (int n = 1; n <= total; ++n) {
    const int k = n <= steps ? n : 2 * steps - n;
    MacroStep s;
    s.t = n * dt;
    s.value[static_cast<std::size_t>(driven)] = sign * to * k / steps;
    if (biaxial)
      s.value[1] = s.value[0]; // E_yy = E_xx
    h.steps.push_back(s);
  }
  return h;
}

} // namespace lamina::homogenize
