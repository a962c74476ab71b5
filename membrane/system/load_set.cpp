#include "membrane/system/load_set.hpp"

#include <algorithm>

namespace lamina::membrane {

LoadSet::LoadSet(const Model& model) : model_(model) {
  has_external_ = !model.loads.empty();
  for (const auto& l : model.surface_loads) {
    has_external_ = has_external_ || l->kind() == WorkKind::External;
    has_drag_ = has_drag_ || l->kind() == WorkKind::Drag;
  }
}

void LoadSet::addSurface(WorkKind kind, const LoadTime& when, const Eigen::VectorXd& u,
                         const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  for (const auto& l : model_.surface_loads)
    if (l->kind() == kind)
      l->add(when, model_.mesh, u, v, f);
}

void LoadSet::external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
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

void LoadSet::drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  f.setZero(model_.numDofs());
  if (!model_.surface_loads.empty())
    addSurface(WorkKind::Drag, 0.0, u, v, f);
}

void LoadSet::springs(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  f.setZero(model_.numDofs());
  for (const auto& s : model_.springs)
    s->add(0.0, model_.mesh, u, u, f);
}

std::vector<Eigen::Vector3d> LoadSet::springSums(const Eigen::VectorXd& u) const {
  std::vector<Eigen::Vector3d> out;
  for (const auto& s : model_.springs)
    out.push_back(s->sum(u));
  return out;
}

void LoadSet::contact(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& su,
                      const Eigen::VectorXd& sv, ContactResult& out) const {
  contactForces(model_.contact, model_.mesh, {u, v, su, sv, mass_, step_}, out);
}

} // namespace lamina::membrane
