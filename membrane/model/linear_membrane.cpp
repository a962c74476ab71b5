#include "membrane/model/linear_membrane.hpp"

#include "core/error.hpp"
#include "membrane/model/stable_step.hpp"

#include <chrono>
#include <cmath>

namespace lamina::membrane {

LinearMembrane::LinearMembrane(const Body& body, bool lumped) : body_(body) {
  for (const Section& s : body.sections) // models are also built by hand, not only from cases
    LAMINA_CHECK(s.isLinear(), "section '", s.name, "' (", s.material, ") has a nonlinear law (",
                 materials::toString(s.law->kind()),
                 "), which the linear (paper's) model cannot carry: use model = "
                 "\"large_deflection\"");
  const auto t0 = std::chrono::steady_clock::now();
  GlobalMatrices g = assemble(body.mesh, body.sections, lumped);
  K_ = std::move(g.K);
  M_ = std::move(g.M);
  MD_ = std::move(g.MD);
  for (const auto& [node, m] : body.point_masses)
    for (int c = 0; c < 3; ++c)
      M_.coeffRef(3 * node + c, 3 * node + c) += m;
  assembly_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void LinearMembrane::internalForce(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  if (!Kb_) // Newmark runs never ask: they use K itself
    Kb_ = std::make_unique<BlockMatrix>(K_);
  Kb_->multiply(u, f);
}

double LinearMembrane::strainEnergy(const Eigen::VectorXd& u) const {
  Eigen::VectorXd y;
  multiply(K_, u, y);
  return 0.5 * u.dot(y);
}

double LinearMembrane::stableStep() const {
  std::vector<double> speed;
  for (const auto& s : body_.sections)
    speed.push_back(std::sqrt(maxWaveModulus(s.D, StrainKind::Lamina6) / s.density));
  return criticalStep(body_.mesh, speed);
}

std::vector<CellField> LinearMembrane::cellFields(const Eigen::VectorXd& u) const {
  const Mesh& mesh = body_.mesh;
  const int ne = mesh.numElements();
  CellField strain{"strain", 6, std::vector<double>(6 * static_cast<size_t>(ne))};
  CellField stress{"stress", 6, std::vector<double>(6 * static_cast<size_t>(ne))};
  for (int e = 0; e < ne; ++e) {
    const auto& tri = mesh.triangles[e];
    Eigen::Matrix<double, 9, 1> ae;
    for (int k = 0; k < 3; ++k)
      ae.segment<3>(3 * k) = u.segment<3>(3 * tri[k]);
    const Eigen::Matrix<double, 6, 1> eps = strainMatrix(mesh, e) * ae;
    const Eigen::Matrix<double, 6, 1> sig = body_.sections[mesh.region_of[e]].D * eps; // eq. (15)
    for (int k = 0; k < 6; ++k) {
      strain.values[6 * static_cast<size_t>(e) + k] = eps[k];
      stress.values[6 * static_cast<size_t>(e) + k] = sig[k];
    }
  }
  return {strain, stress};
}

} // namespace lamina::membrane
