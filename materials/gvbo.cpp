#include "materials/gvbo.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::materials {

GvboParameters readGvboParameters(const core::TableReader& g, double E0, double nu0) {
  GvboParameters p;
  p.E0 = E0;
  p.nu0 = nu0;
  p.Et = g.getDouble("Et");
  p.p = g.getDouble("p");
  p.a1 = g.getDouble("a1");
  p.a2 = g.getDouble("a2");
  p.a3 = g.getDouble("a3");
  p.k1 = g.getDouble("k1");
  p.k2 = g.getDouble("k2");
  p.k3 = g.getDouble("k3");
  p.k4 = g.getDouble("k4");
  p.Em = g.getDouble("Em");
  p.A0 = g.getDouble("A0");
  p.Ac = g.getDouble("Ac");
  p.Af = g.getDouble("Af");
  return p;
}

GvboModuli gvboModuli(const GvboParameters& g, double J) {
  LAMINA_CHECK(J > 0 && std::isfinite(J), "GVBO state J must be positive, got ", J);
  // eq. (15)
  const double lambda0 = g.E0 * g.nu0 / ((1 + g.nu0) * (1 - 2 * g.nu0));
  const double G0 = g.E0 / (2 * (1 + g.nu0));
  // eq. (13), clamped from below (text after eq. (16))
  const double Jp = std::pow(J, g.p);
  const double lambda = std::max(lambda0, Jp * lambda0);
  const double G = std::max(G0, Jp * (G0 - lambda0 * std::log(J)));
  // eq. (16)
  double E = G * (3 * lambda + 2 * G) / (lambda + G);
  const double nu = lambda / (2 * (lambda + G));
  E = std::max(E, g.E0); // never below E0; with lambda >= lambda0, G >= G0 this holds already
  return {lambda, G, E, nu};
}

} // namespace lamina::materials
