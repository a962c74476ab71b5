#include "membrane/model/constraint.hpp"

namespace lamina::membrane {

ConstrainedDofs::ConstrainedDofs(const std::vector<Constraint>& sets, int ndof)
    : sets_(&sets), mask_(ndof, 0) {
  for (size_t s = 0; s < sets.size(); ++s) {
    const auto& con = sets[s];
    for (size_t k = 0; k < con.dofs.size(); ++k) {
      dofs_.push_back(con.dofs[k]);
      set_.push_back(static_cast<int>(s));
      amplitude_.push_back(con.amplitude[k]);
      mask_[con.dofs[k]] = 1;
    }
  }
}

void ConstrainedDofs::prescribe(double t, Eigen::VectorXd& v) const {
  for (size_t k = 0; k < dofs_.size(); ++k)
    v[dofs_[k]] = velocity(k, t);
}

std::vector<Eigen::Vector3d> ConstrainedDofs::sums(const Eigen::VectorXd& r) const {
  std::vector<Eigen::Vector3d> s(sets_ ? sets_->size() : 0, Eigen::Vector3d::Zero());
  for (size_t k = 0; k < dofs_.size(); ++k)
    s[set_[k]][dofs_[k] % 3] += r[static_cast<Eigen::Index>(k)];
  return s;
}

} // namespace lamina::membrane
