#include "membrane/loads/load_set.hpp"

namespace lamina::membrane {

LoadSet::LoadSet(const Model& model) : model_(model) {}

void LoadSet::external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  (void)u; // the fixed patterns of the linear model do not follow the surface
  f.setZero(model_.numDofs());
  for (const auto& l : model_.loads) {
    const double s = l.profile(t);
    if (s != 0)
      f += s * l.pattern;
  }
}

void LoadSet::drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  (void)u;
  f.setZero(model_.numDofs());
  for (const auto& d : model_.drags)
    addDragForce(d, v, f);
}

} // namespace lamina::membrane
