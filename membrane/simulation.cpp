#include "membrane/simulation.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "membrane/integrators/central_difference.hpp"
#include "membrane/integrators/newmark.hpp"
#include "membrane/integrators/step_solver.hpp"
#include "membrane/model/large_deflection.hpp"
#include "membrane/model/linear_membrane.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::membrane {

namespace {
std::unique_ptr<Structure> makeStructure(const Model& model) {
  if (model.kind == ModelKind::LargeDeflection)
    return std::make_unique<LargeDeflection>(model);
  return std::make_unique<LinearMembrane>(model);
}

/// The stable step of @p structure with the model's springs: a spring k on a
/// node of lumped mass m adds k / m to omega^2 there, so the bound
/// omega_max = 2 / dt_s of the structure becomes sqrt((2 / dt_s)^2 + k / m).
double stableWithSprings(const Model& model, const Structure& structure) {
  const double dt = structure.stableStep();
  if (model.springs.empty())
    return dt;
  const SparseMatrix& M = structure.mass();
  double w2 = 0;
  for (const auto& s : model.springs)
    for (int d : s->dofs()) {
      double m = 0;
      for (SparseMatrix::InnerIterator it(M, d); it; ++it)
        m += it.value();
      w2 = std::max(w2, s->stiffness() / m);
    }
  return 2 / std::sqrt(4 / (dt * dt) + w2);
}

/// The explicit step: time.dt when given (at most the stable step), else safety x stable.
double explicitStep(const TimeSettings& ts, double stable) {
  if (ts.dt > 0) {
    if (ts.dt > stable)
      throw Error("time.dt = " + core::formatShort(ts.dt) + " s exceeds the stable step " +
                  core::formatShort(stable) +
                  " s of the explicit integrator (leave dt out for safety x stable step)");
    return ts.dt;
  }
  return ts.safety * stable;
}
} // namespace

Simulation::Simulation(const Model& model)
    : model_(model), structure_(makeStructure(model)), loads_(model),
      cons_(model.constraints, model.numDofs()) {
  stable_dt_ = stableWithSprings(model, *structure_);
  if (model.time.integrator == IntegratorKind::Explicit)
    integrator_ = std::make_unique<CentralDifference>(model, *structure_, loads_, cons_,
                                                      explicitStep(model.time, stable_dt_),
                                                      model.time.damping);
  else
    integrator_ = std::make_unique<Newmark>(model, *structure_, loads_, cons_);
  const int ndof = model.numDofs();
  state_.u = model.u0.size() == ndof ? model.u0 : Eigen::VectorXd::Zero(ndof);
  state_.v = model.v0.size() == ndof ? model.v0 : Eigen::VectorXd::Zero(ndof);
  cons_.prescribe(0.0, state_.v);
  integrator_->init(state_);
  u0_ = structure_->strainEnergy(state_.u);
  const Energy e = energy();
  e0_ = e.kinetic + e.strain;
  structure_->checkFailure(state_.t, state_.u, failure_);
}

Simulation::~Simulation() = default;

void Simulation::step() {
  integrator_->step(state_);
  works_.add(integrator_->increment(), integrator_->previousForces(), integrator_->forces(), cons_,
             loads_.hasExternal(), loads_.hasDrag());
  if (structure_->hasFailureThresholds())
    structure_->checkFailure(state_.t, state_.u, failure_);
}

Energy Simulation::energy() const {
  Eigen::VectorXd y;
  multiply(structure_->mass(), state_.v, y);
  const double T = 0.5 * state_.v.dot(y);
  // Without a potential (tension-only fabric) U is the internal work done since t = 0.
  const double U =
      structure_->hasPotential() ? structure_->strainEnergy(state_.u) : u0_ + works_.internal;
  Energy e = works_.energy(T, U, e0_);
  if (const SparseMatrix* MD = structure_->microMass()) {
    multiply(*MD, state_.v, y);
    e.micro_kinetic = 0.5 * state_.v.dot(y);
  }
  return e;
}

std::vector<Eigen::Vector3d> Simulation::reactionSums() const {
  auto s = cons_.sums(integrator_->forces().reaction);
  for (const auto& f : loads_.springSums(state_.u))
    s.push_back(f);
  return s;
}

std::vector<std::string> Simulation::reactionNames() const {
  std::vector<std::string> names;
  for (const auto& c : model_.constraints)
    names.push_back(c.name);
  for (const auto& s : model_.springs)
    names.push_back(s->name());
  return names;
}

Eigen::Vector3d Simulation::dragSum() const {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  const auto& fd = integrator_->forces().drag;
  if (fd.size() == 0)
    return s;
  for (int i = 0; i < model_.mesh.numNodes(); ++i)
    s += fd.segment<3>(3 * i);
  return s;
}

const SparseMatrix& Simulation::K() const {
  LAMINA_CHECK(structure_->stiffness() != nullptr, "the model has no constant stiffness K");
  return *structure_->stiffness();
}

} // namespace lamina::membrane
