#include "membrane/model/stable_step.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lamina::membrane {

double maxWaveModulus(const Eigen::MatrixXd& D, StrainKind kind) {
  constexpr double kPi = 3.14159265358979323846;
  double best = 0;
  for (int k = 0; k < 180; ++k) {
    const double th = kPi * k / 180, n1 = std::cos(th), n2 = std::sin(th);
    Eigen::MatrixXd B;
    if (kind == StrainKind::Lamina6) {
      B = Eigen::MatrixXd::Zero(6, 3);
      B(0, 0) = n1; // u_x
      B(1, 1) = n2; // v_y
      B(3, 0) = n2; // u_y + v_x
      B(3, 1) = n1;
      B(4, 2) = n2; // w_y
      B(5, 2) = n1; // w_x
    } else {
      B = Eigen::MatrixXd::Zero(3, 2);
      B(0, 0) = n1;
      B(1, 1) = n2;
      B(2, 0) = n2;
      B(2, 1) = n1;
    }
    const Eigen::MatrixXd G = B.transpose() * D * B;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G, Eigen::EigenvaluesOnly);
    best = std::max(best, es.eigenvalues().maxCoeff());
  }
  return best;
}

double elementLength(const Mesh& mesh, int e) {
  const auto& t = mesh.triangles[e];
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (mesh.point(t[k]) - mesh.point(t[(k + 1) % 3])).norm());
  return 2 * mesh.area3(e) / longest;
}

double criticalStep(const Mesh& mesh, const std::vector<double>& speed) {
  double dt = std::numeric_limits<double>::infinity();
  for (int e = 0; e < mesh.numElements(); ++e)
    dt = std::min(dt, elementLength(mesh, e) / speed[mesh.region_of[e]]);
  return dt;
}

} // namespace lamina::membrane
