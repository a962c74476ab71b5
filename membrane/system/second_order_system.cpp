#include "membrane/system/second_order_system.hpp"

#include "membrane/model/large_deflection.hpp"
#include "membrane/model/linear_membrane.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::membrane {

namespace {
std::unique_ptr<Structure> makeStructure(const Model& model) {
  if (model.kind == ModelKind::LargeDeflection)
    return std::make_unique<LargeDeflection>(model);
  return std::make_unique<LinearMembrane>(model, model.time.lumped);
}

/// @return the row sums of @p M (the lumped mass per DOF, kg)
Eigen::VectorXd rowSums(const SparseMatrix& M) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(M.rows());
  for (int d = 0; d < M.rows(); ++d)
    for (SparseMatrix::InnerIterator it(M, d); it; ++it)
      m[d] += it.value();
  return m;
}
} // namespace

SecondOrderSystem::SecondOrderSystem(const Model& model)
    : model_(model), structure_(makeStructure(model)), cons_(model.constraints, model.numDofs()),
      lumped_(rowSums(structure_->mass())) {
  has_external_ = !model.loads.empty();
  for (const auto& l : model.surface_loads) {
    has_external_ = has_external_ || l->kind() == WorkKind::External;
    has_drag_ = has_drag_ || l->kind() == WorkKind::Drag;
  }
  if (const SparseMatrix* K = structure_->stiffness()) {
    stiffness_ = K;
    if (!model.springs.empty()) { // K_s on the diagonal (K's 3x3 diagonal blocks are stored)
      stiffness_springs_ = *K;
      for (const auto& s : model.springs)
        for (int d : s->dofs())
          stiffness_springs_.coeffRef(d, d) += s->stiffness();
      stiffness_ = &stiffness_springs_;
    }
  }
}

SecondOrderSystem::~SecondOrderSystem() = default;

void SecondOrderSystem::setStep(double dt) {
  half_step_ = 0.5 * dt;
  step_ = dt;
}

void SecondOrderSystem::addSurface(WorkKind kind, const LoadTime& when, const Eigen::VectorXd& u,
                                   const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  for (const auto& l : model_.surface_loads)
    if (l->kind() == kind)
      l->add(when, model_.mesh, u, v, f);
}

void SecondOrderSystem::external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  f.setZero(model_.numDofs());
  const LoadTime when(t, std::max(0.0, t - half_step_), t + half_step_);
  for (const auto& l : model_.loads) {
    const double s = when.mean(l.profile.integral(when.from, when.to), l.profile(t));
    if (s != 0)
      f += s * l.pattern;
  }
  if (!model_.surface_loads.empty())
    addSurface(WorkKind::External, when, u, Eigen::VectorXd(), f); // pressures ignore v
}

void SecondOrderSystem::drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                             Eigen::VectorXd& f) const {
  f.setZero(model_.numDofs());
  if (!model_.surface_loads.empty())
    addSurface(WorkKind::Drag, 0.0, u, v, f);
}

void SecondOrderSystem::springs(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  f.setZero(model_.numDofs());
  for (const auto& s : model_.springs)
    s->add(0.0, model_.mesh, u, u, f);
}

void SecondOrderSystem::contact(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& su, const Eigen::VectorXd& sv,
                                ContactResult& out) const {
  contactForces(model_.contact, model_.mesh, {u, v, su, sv, lumped_, step_}, out);
}

void SecondOrderSystem::forces(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                               const Eigen::VectorXd& su, const Eigen::VectorXd& sv,
                               StateForces& f) const {
  const int ndof = numDofs();
  // Without loads or drag their forces stay the zero vectors of the first call.
  if (has_external_ || f.external.size() != ndof)
    external(t, u, f.external);
  if (has_drag_)
    drag(u, v, f.drag);
  else if (f.drag.size() != ndof)
    f.drag = Eigen::VectorXd::Zero(ndof);
  if (hasSprings())
    springs(u, f.spring);
  if (hasDamping())
    f.damping = -model_.time.damping * lumped_.cwiseProduct(v);
  if (hasContact())
    contact(u, v, su, sv, f.contact);
  structure_->internalForce(u, f.internal);
}

void SecondOrderSystem::reactions(const Eigen::VectorXd& inertia, StateForces& f) const {
  f.reaction.resize(static_cast<Eigen::Index>(cons_.size()));
  for (size_t k = 0; k < cons_.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const int d = cons_.dofs()[k];
    double r = inertia[i] - (f.external[d] + f.drag[d]);
    if (f.spring.size())
      r -= f.spring[d];
    if (f.damping.size())
      r -= f.damping[d];
    if (f.contact.force.size())
      r -= f.contact.force[d];
    f.reaction[i] = r;
  }
}

void SecondOrderSystem::addWorks(Works& works, const Eigen::VectorXd& du, const StateForces& f0,
                                 const StateForces& f1) const {
  works.add(du, f0, f1, cons_, has_external_, has_drag_);
}

std::vector<Eigen::Vector3d> SecondOrderSystem::reactionSums(const StateForces& f,
                                                             const Eigen::VectorXd& u) const {
  auto s = cons_.sums(f.reaction);
  for (const auto& spring : model_.springs)
    s.push_back(spring->sum(u));
  const Eigen::VectorXd& c = f.contact.sum;
  for (Eigen::Index k = 0; k < c.size() / 3; ++k)
    s.emplace_back(c.segment<3>(3 * k));
  return s;
}

std::vector<std::string> SecondOrderSystem::reactionNames() const {
  std::vector<std::string> names;
  for (const auto& c : model_.constraints)
    names.push_back(c.name);
  for (const auto& s : model_.springs)
    names.push_back(s->name());
  for (const auto& s : model_.contact)
    names.push_back(s.name);
  return names;
}

Eigen::Vector3d SecondOrderSystem::dragSum(const StateForces& f) const {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  if (f.drag.size() == 0)
    return s;
  for (int i = 0; i < model_.mesh.numNodes(); ++i)
    s += f.drag.segment<3>(3 * i);
  return s;
}

double SecondOrderSystem::stableStep() const {
  return withSprings(structure_->stableStep());
}

double SecondOrderSystem::currentStableStep(const Eigen::VectorXd& u) const {
  return withSprings(structure_->currentStableStep(u));
}

double SecondOrderSystem::withSprings(double dt) const {
  if (model_.springs.empty() && model_.contact.empty())
    return dt;
  double w2 = 0;
  for (const auto& s : model_.springs)
    for (int d : s->dofs())
      w2 = std::max(w2, s->stiffness() / lumped_[d]);
  if (!model_.contact.empty())
    w2 += penaltyOmega2(model_.contact, lumped_);
  return 2 / std::sqrt(4 / (dt * dt) + w2);
}

} // namespace lamina::membrane
