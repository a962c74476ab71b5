#include "membrane/integrators/central_difference.hpp"

#include <cmath>
#include <sstream>

namespace lamina::membrane {

CentralDifference::CentralDifference(const Model& model, const Structure& structure,
                                     const LoadSet& loads, const ConstrainedDofs& cons, double dt,
                                     double damping)
    : model_(model), structure_(structure), loads_(loads), cons_(cons), dt_(dt), damping_(damping) {
  LAMINA_CHECK(dt > 0 && std::isfinite(dt), "explicit time step must be > 0");
  LAMINA_CHECK(damping >= 0, "damping must be >= 0");
  const int ndof = structure.numDofs();
  // Lumped mass: row sums (the diagonal itself for a lumped model).
  const SparseMatrix& M = structure.mass();
  m_ = Eigen::VectorXd::Zero(ndof);
  for (int i = 0; i < ndof; ++i)
    for (SparseMatrix::InnerIterator it(M, i); it; ++it)
      m_[i] += it.value();
  minv_ = Eigen::VectorXd::Zero(ndof);
  for (int i = 0; i < ndof; ++i) {
    LAMINA_CHECK(m_[i] > 0, "explicit integration: DOF ", i, " (node ", i / 3, ") has no mass");
    minv_[i] = cons.mask()[i] ? 0.0 : 1.0 / m_[i];
  }
  for (const auto& r : model.rigid) {
    double m = 0;
    for (int d : r.dofs)
      m += m_[d];
    rigid_mass_.push_back(m);
  }
}

void CentralDifference::evaluate(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                 StateForces& f) {
  const int ndof = structure_.numDofs();
  loads_.external(t, u, f.external);
  if (loads_.hasDrag())
    loads_.drag(u, v, f.drag);
  else if (f.drag.size() != ndof)
    f.drag = Eigen::VectorXd::Zero(ndof);
  if (loads_.hasSprings())
    loads_.springs(u, f.spring);
  if (damping_ > 0)
    f.damping = -damping_ * m_.cwiseProduct(v);
  structure_.internalForce(u, f.internal);
}

void CentralDifference::accelerate(const StateForces& f, Eigen::VectorXd& a) const {
  Eigen::VectorXd total = f.external + f.drag - f.internal;
  if (f.spring.size())
    total += f.spring;
  if (f.damping.size())
    total += f.damping;
  a = minv_.cwiseProduct(total);
  for (size_t k = 0; k < model_.rigid.size(); ++k) {
    double sum = 0;
    for (int d : model_.rigid[k].dofs)
      sum += total[d];
    for (int d : model_.rigid[k].dofs)
      a[d] = sum / rigid_mass_[k];
  }
}

void CentralDifference::reactions(const Eigen::VectorXd& a, StateForces& f) const {
  f.reaction.resize(static_cast<Eigen::Index>(cons_.size()));
  for (size_t k = 0; k < cons_.size(); ++k) {
    const int d = cons_.dofs()[k];
    double r = m_[d] * a[d] + f.internal[d] - f.external[d] - f.drag[d];
    if (f.spring.size())
      r -= f.spring[d];
    if (f.damping.size())
      r -= f.damping[d];
    f.reaction[static_cast<Eigen::Index>(k)] = r;
  }
}

void CentralDifference::init(State& s) {
  evaluate(s.t, s.u, s.v, cur_);
  accelerate(cur_, s.a);
  for (int d : cons_.dofs())
    s.a[d] = 0;
  reactions(s.a, cur_);
  prev_ = cur_;
  du_ = Eigen::VectorXd::Zero(structure_.numDofs());
}

void CentralDifference::step(State& s) {
  const double t1 = static_cast<double>(s.step + 1) * dt_;
  const double th = (static_cast<double>(s.step) + 0.5) * dt_;
  vh_ = s.v + (0.5 * dt_) * s.a;
  for (size_t k = 0; k < cons_.size(); ++k)
    vh_[cons_.dofs()[k]] = cons_.velocity(k, th);
  u1_ = s.u + dt_ * vh_;
  StateForces& next = prev_; // a_{n-1}'s forces are no longer needed
  evaluate(t1, u1_, vh_, next);
  accelerate(next, a1_);
  v1_ = vh_ + (0.5 * dt_) * a1_;
  for (size_t k = 0; k < cons_.size(); ++k) {
    const int d = cons_.dofs()[k];
    v1_[d] = cons_.velocity(k, t1);
    a1_[d] = (v1_[d] - s.v[d]) / dt_;
  }
  if (!u1_.allFinite() || !v1_.allFinite() || !a1_.allFinite())
    throwNonFinite(model_.mesh, s, t1, u1_, v1_, a1_,
                   "; the explicit step may exceed the stable step");
  reactions(a1_, next);
  du_ = u1_ - s.u;
  std::swap(s.u, u1_);
  std::swap(s.v, v1_);
  std::swap(s.a, a1_);
  s.t = t1;
  ++s.step;
  std::swap(prev_, cur_);
}

} // namespace lamina::membrane
