#include "materials/gvbo.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::materials {

const std::array<std::pair<const char*, double GvboParameters::*>, 13>& gvboTableKeys() {
  static const std::array<std::pair<const char*, double GvboParameters::*>, 13> keys{{
      {"Et", &GvboParameters::Et},
      {"p", &GvboParameters::p},
      {"a1", &GvboParameters::a1},
      {"a2", &GvboParameters::a2},
      {"a3", &GvboParameters::a3},
      {"k1", &GvboParameters::k1},
      {"k2", &GvboParameters::k2},
      {"k3", &GvboParameters::k3},
      {"k4", &GvboParameters::k4},
      {"Em", &GvboParameters::Em},
      {"A0", &GvboParameters::A0},
      {"Ac", &GvboParameters::Ac},
      {"Af", &GvboParameters::Af},
  }};
  return keys;
}

GvboParameters readGvboParameters(const core::TableReader& g, double E0, double nu0) {
  GvboParameters p;
  p.E0 = E0;
  p.nu0 = nu0;
  for (const auto& [key, member] : gvboTableKeys())
    p.*member = g.getDouble(key);
  return p;
}

GvboModuli gvboModuli(const GvboParameters& g, double J) {
  LAMINA_CHECK(J > 0 && std::isfinite(J), "GVBO state J must be positive, got ", J);
  // eq. (15)
  const double lambda0 = g.E0 * g.nu0 / ((1 + g.nu0) * (1 - 2 * g.nu0));
  const double G0 = g.E0 / (2 * (1 + g.nu0));
  // eq. (13), clamped from below (text after eq. (16))
  // J^p as exp(p ln J): one logarithm serves both terms (pow would take its own)
  const double lnJ = std::log(J);
  const double Jp = std::exp(g.p * lnJ);
  const double lambda = std::max(lambda0, Jp * lambda0);
  const double G = std::max(G0, Jp * (G0 - lambda0 * lnJ));
  // eq. (16)
  double E = G * (3 * lambda + 2 * G) / (lambda + G);
  const double nu = lambda / (2 * (lambda + G));
  E = std::max(E, g.E0); // never below E0; with lambda >= lambda0, G >= G0 this holds already
  return {lambda, G, E, nu};
}

} // namespace lamina::materials
