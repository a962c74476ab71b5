#include "materials/fabric_law.hpp"

#include "core/error.hpp"
#include "core/toml_reader.hpp"
#include "materials/plane_stress.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace lamina::materials {

double FabricParameters::transverseModulus() const {
  return kFabricTransverseFraction * std::max({warp.maxSlope(), fill.maxSlope(), G12});
}

namespace {

/// A modulus key: positive and finite (Pa).
double modulus(const core::TableReader& t, const char* key) {
  const double v = t.getDouble(key);
  if (!(v > 0) || !std::isfinite(v))
    t.fail(key, "must be positive (Pa)");
  return v;
}

/// One yarn direction: the modulus @p modulus_key or the curve file @p curve_key, not both.
YarnCurve readYarn(const core::TableReader& t, const char* modulus_key, const char* curve_key) {
  const bool has_modulus = t.has(modulus_key), has_curve = t.has(curve_key);
  if (has_modulus && has_curve)
    t.fail(curve_key, std::string("give either ") + modulus_key + " or " + curve_key +
                          " for this yarn direction, not both");
  if (!has_curve) {
    if (!has_modulus)
      t.fail(modulus_key, std::string("missing: the fabric law needs ") + modulus_key +
                              " (Pa) or a stress-strain curve " + curve_key + " (CSV)");
    return YarnCurve::linear(modulus(t, modulus_key));
  }
  std::filesystem::path file = t.getString(curve_key);
  if (file.empty())
    t.fail(curve_key, "must name a CSV file (strain, stress in Pa)");
  if (file.is_relative() && !t.file().empty())
    file = std::filesystem::path(t.file()).parent_path() / file;
  return readYarnCurveCsv(file.lexically_normal().string(), t.path(curve_key));
}

} // namespace

FabricParameters readFabricParameters(const core::TableReader& t) {
  FabricParameters p;
  p.warp = readYarn(t, "E_warp", "warp_curve");
  p.fill = readYarn(t, "E_fill", "fill_curve");
  p.G12 = modulus(t, "G12");
  if (t.has("nu12") && t.getDouble("nu12") != 0)
    t.fail("nu12", "the fabric law has no Poisson coupling between warp and fill: nu12 must be 0 "
                   "(or left out)");
  return p;
}

FabricLaw::FabricLaw(FabricParameters p) : p_(std::move(p)), Et_(p_.transverseModulus()) {
  LAMINA_CHECK(p_.G12 > 0 && std::isfinite(p_.G12), "fabric G12 must be positive (", p_.G12, ")");
}

Stiffness FabricLaw::elasticStiffness(double J) const {
  Vector6 d;
  d << p_.warp.maxSlope(), p_.fill.maxSlope(), Et_, p_.G12, Et_, Et_;
  return Stiffness(Matrix6(d.asDiagonal()) / J);
}

double FabricLaw::energy(const Vector6& e) const {
  return p_.warp.energy(e[0]) + p_.fill.energy(e[1]) + 0.5 * p_.G12 * e[3] * e[3] +
         0.5 * Et_ * (e[2] * e[2] + e[4] * e[4] + e[5] * e[5]);
}

void FabricLaw::update(const PointStep& step, const double*, double* state, Vector6& sigma,
                       Matrix6* tangent) const {
  const Vector6& e = step.eps;
  LAMINA_CHECK(step.J > 0 && std::isfinite(step.J), "fabric law: volume ratio J = ", step.J,
               " is not positive");
  Vector6 tau;
  tau << p_.warp.stress(e[0]), p_.fill.stress(e[1]), Et_ * e[2], p_.G12 * e[3], Et_ * e[4],
      Et_ * e[5];
  sigma = tau / step.J;
  state[kEnergy] = energy(e);
  if (tangent) {
    Vector6 d;
    d << p_.warp.tangent(e[0]), p_.fill.tangent(e[1]), Et_, p_.G12, Et_, Et_;
    *tangent = Matrix6(d.asDiagonal()) / step.J;
  }
}

bool FabricLaw::planeStressStep(const PlaneStressStep& ps, const double* state_n, double* state,
                                double tolerance, PlaneStressResult& out) const {
  if (ps.n_free != 0)
    return false;
  // planeStressUpdate()'s predictor and its first test, z = 0: the strain of
  // t_n plus the imposed in-plane increment, the thickness stretch of t_n.
  PointStep step;
  step.eps_n = ps.eps_n;
  step.eps = strainAtEnd(ps, 0.0);
  step.J_n = ps.J2_n * ps.lambda3_n;
  const double lambda3 = midpointThicknessStretch(ps.lambda3_n, 0.0);
  step.J = ps.J2 * lambda3;
  step.dt = ps.dt;
  double trial[1];
  Vector6 sigma;
  update(step, state_n, trial, sigma, nullptr);
  if (!sigma.allFinite())
    return false; // the Newton refuses it, with its message
  const double residual =
      std::max({std::abs(sigma[2]), std::abs(sigma[4]), std::abs(sigma[5])}); // zz, yz, xz
  // max |elasticStiffness(J_n)|: the largest diagonal entry / J_n, exactly
  // (rounding is monotone)
  const double max_modulus = std::max({p_.warp.maxSlope(), p_.fill.maxSlope(), Et_, p_.G12});
  if (!(residual <=
        tolerance * planeStressScale(sigma, max_modulus / step.J_n, ps.eps_n, step.eps)))
    return false; // out-of-plane strain left at t_n: the Newton removes it
  state[kEnergy] = trial[kEnergy];
  out.eps = step.eps;
  out.lambda3 = lambda3;
  out.sigma = sigma;
  out.iterations = 0;
  out.residual = residual;
  return true;
}

double FabricLaw::storedEnergy(const Vector6&, const double* state, double J) const {
  LAMINA_CHECK(state != nullptr, "the fabric law's stored energy needs its state");
  return state[kEnergy] / J;
}

} // namespace lamina::materials
