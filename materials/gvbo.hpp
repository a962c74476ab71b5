#pragma once
/// @file gvbo.hpp
/// @brief Parameters of the GVBO polymer law (polyurea chapter, Table 1) and
/// its deformation-dependent elastic moduli (eqs. 13-16).

#include "core/toml_reader.hpp"

#include <array>
#include <string>
#include <utility>

namespace lamina::materials {

/// The 15 GVBO parameters (chapter Table 1), SI units (Pa, 1/Pa, 1/s).
struct GvboParameters {
  double E0 = 0;         ///< initial Young's modulus (Pa)
  double nu0 = 0;        ///< initial Poisson ratio
  double Et = 0;         ///< tangent modulus (Pa)
  double p = 0;          ///< exponent of J in eq. (13)
  double a1 = 0, a2 = 0; ///< shape function constants (Pa)
  double a3 = 0;         ///< shape function constant (1/Pa)
  double k1 = 0;         ///< viscosity constant (-)
  double k2 = 0, k3 = 0; ///< viscosity constants (Pa)
  double k4 = 0;         ///< viscosity exponent (-)
  double Em = 0;         ///< maximum Young's modulus (Pa)
  double A0 = 0;         ///< initial isotropic stress (Pa)
  double Ac = 0;         ///< isotropic stress rate constant (1/s)
  double Af = 0;         ///< final isotropic stress (Pa)
};

/// The keys of a `gvbo` table (Et, p, a1, a2, a3, k1, k2, k3, k4, Em, A0, Ac,
/// Af) and the parameter each holds: the one list for reading and writing.
const std::array<std::pair<const char*, double GvboParameters::*>, 13>& gvboTableKeys();

/// Reads the GVBO parameters other than E0, nu0 from table @p g (the keys of
/// gvboTableKeys(); SI units), all required.
GvboParameters readGvboParameters(const core::TableReader& g, double E0, double nu0);

/// Instantaneous isotropic moduli of a GVBO phase at volume ratio J.
struct GvboModuli {
  double lambda; ///< Lame lambda[J] (Pa)
  double G;      ///< shear modulus G[J] (Pa)
  double E;      ///< Young's modulus E[J] (Pa)
  double nu;     ///< Poisson ratio nu[J]
};

/// Moduli at J > 0 by eqs. (13)-(16) of the polyurea chapter:
/// lambda = J^p lambda0, G = J^p (G0 - lambda0 ln J), with the rule that
/// G, lambda and E never drop below their initial values (each is replaced
/// by its initial value when eq. (13) would lower it). J = 1 gives E0, nu0.
GvboModuli gvboModuli(const GvboParameters& g, double J);

} // namespace lamina::materials
