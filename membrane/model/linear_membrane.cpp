#include "membrane/model/linear_membrane.hpp"

#include "membrane/integrators/step_solver.hpp"

#include <chrono>

namespace lamina::membrane {

LinearMembrane::LinearMembrane(const Model& model) {
  const auto t0 = std::chrono::steady_clock::now();
  GlobalMatrices g = assemble(model.mesh, model.sections, model.time.lumped);
  K_ = std::move(g.K);
  M_ = std::move(g.M);
  for (const auto& [node, m] : model.point_masses)
    for (int c = 0; c < 3; ++c)
      M_.coeffRef(3 * node + c, 3 * node + c) += m;
  assembly_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void LinearMembrane::internalForce(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  multiply(K_, u, f);
}

double LinearMembrane::strainEnergy(const Eigen::VectorXd& u) const {
  Eigen::VectorXd y;
  multiply(K_, u, y);
  return 0.5 * u.dot(y);
}

} // namespace lamina::membrane
