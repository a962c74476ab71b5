#include "membrane/loads/follower_drag.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::membrane {

FollowerDrag::FollowerDrag(std::string name, std::vector<int> elements, double cd, double rho,
                           bool resultant)
    : name_(std::move(name)), elements_(std::move(elements)), cd_(cd), rho_(rho),
      resultant_(resultant) {}

void FollowerDrag::add(const LoadTime&, const Mesh& mesh, const Eigen::VectorXd& u,
                       const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  const int n = mesh.numNodes();
  // Current area vectors (sum of A_e n_e / 3) and tributary areas per node.
  std::vector<Eigen::Vector3d> an(n, Eigen::Vector3d::Zero());
  std::vector<double> area(n, 0.0);
  std::vector<char> used(n, 0);
  for (int e : elements_) {
    const auto& tri = mesh.triangles[e];
    std::array<Eigen::Vector3d, 3> x;
    for (int a = 0; a < 3; ++a)
      x[a] = mesh.point(tri[a]) + u.segment<3>(3 * tri[a]);
    const Eigen::Vector3d ae = (x[1] - x[0]).cross(x[2] - x[0]) / 6.0; // A_e n_e / 3
    const double third = ae.norm();
    for (int i : tri) {
      an[i] += ae;
      area[i] += third;
      used[i] = 1;
    }
  }
  const double half = 0.5 * rho_ * cd_;
  for (int i = 0; i < n; ++i) {
    if (!used[i] || !(an[i].norm() > 0))
      continue;
    const Eigen::Vector3d nrm = an[i].normalized();
    const Eigen::Vector3d vi = v.segment<3>(3 * i);
    const double vn = vi.dot(nrm);
    const double q = half * area[i];
    const double mag =
        resultant_ ? q * vi.squaredNorm() * ((vn > 0) - (vn < 0)) : q * std::abs(vn) * vn;
    f.segment<3>(3 * i) -= mag * nrm;
  }
}

} // namespace lamina::membrane
