#include "membrane/loads/ground_springs.hpp"

namespace lamina::membrane {

GroundSprings::GroundSprings(std::string name, std::vector<int> dofs, double k)
    : name_(std::move(name)), dofs_(std::move(dofs)), k_(k) {}

void GroundSprings::add(const LoadTime&, const Mesh&, const Eigen::VectorXd& u,
                        const Eigen::VectorXd&, Eigen::VectorXd& f) const {
  for (int d : dofs_)
    f[d] -= k_ * u[d];
}

Eigen::Vector3d GroundSprings::sum(const Eigen::VectorXd& u) const {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int d : dofs_)
    s[d % 3] -= k_ * u[d];
  return s;
}

} // namespace lamina::membrane
