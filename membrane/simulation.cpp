#include "membrane/simulation.hpp"

#include "core/error.hpp"
#include "membrane/integrators/newmark.hpp"
#include "membrane/integrators/step_solver.hpp"
#include "membrane/model/linear_membrane.hpp"

namespace lamina::membrane {

Simulation::Simulation(const Model& model)
    : model_(model), structure_(std::make_unique<LinearMembrane>(model)), loads_(model),
      cons_(model.constraints, model.numDofs()) {
  integrator_ = std::make_unique<Newmark>(model, *structure_, loads_, cons_);
  const int ndof = model.numDofs();
  state_.u = model.u0.size() == ndof ? model.u0 : Eigen::VectorXd::Zero(ndof);
  state_.v = model.v0.size() == ndof ? model.v0 : Eigen::VectorXd::Zero(ndof);
  cons_.prescribe(0.0, state_.v);
  integrator_->init(state_);
  const Energy e = energy();
  e0_ = e.kinetic + e.strain;
}

Simulation::~Simulation() = default;

void Simulation::step() {
  integrator_->step(state_);
  works_.add(integrator_->increment(), integrator_->previousForces(), integrator_->forces(), cons_,
             loads_.hasExternal(), loads_.hasDrag());
}

Energy Simulation::energy() const {
  Eigen::VectorXd y;
  multiply(structure_->mass(), state_.v, y);
  const double T = 0.5 * state_.v.dot(y);
  return works_.energy(T, structure_->strainEnergy(state_.u), e0_);
}

std::vector<Eigen::Vector3d> Simulation::reactionSums() const {
  return cons_.sums(integrator_->forces().reaction);
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
