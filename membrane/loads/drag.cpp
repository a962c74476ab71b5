#include "membrane/loads/drag.hpp"

#include <cmath>

namespace lamina::membrane {

Drag::Drag(std::string name, const Mesh& mesh, std::vector<int> elements, const DragSpec& spec)
    : name_(std::move(name)), elements_(std::move(elements)), spec_(spec) {
  const int n = mesh.numNodes();
  node_area_.assign(static_cast<size_t>(n), 0.0);
  node_normal_.assign(static_cast<size_t>(n), Eigen::Vector3d::Zero());
  for (int e : elements_) {
    // The plan area on a flat mesh (the linear model's), else the true one.
    const double third = (mesh.flat() ? mesh.area(e) : mesh.area3(e)) / 3;
    element_third_.push_back(third);
    const Eigen::Vector3d ae = thirdAreaVector(mesh, e, Eigen::VectorXd());
    for (int i : mesh.triangles[e]) {
      node_area_[static_cast<size_t>(i)] += third;
      node_normal_[static_cast<size_t>(i)] += ae;
    }
  }
}

Eigen::Vector3d Drag::thirdAreaVector(const Mesh& mesh, int e, const Eigen::VectorXd& u) const {
  const auto& tri = mesh.triangles[e];
  std::array<Eigen::Vector3d, 3> x;
  for (int a = 0; a < 3; ++a)
    x[a] = u.size() ? Eigen::Vector3d(mesh.point(tri[a]) + u.segment<3>(3 * tri[a]))
                    : mesh.point(tri[a]);
  return (x[1] - x[0]).cross(x[2] - x[0]) / 6.0; // A_e n_e / 3
}

Eigen::Vector3d Drag::nodeForce(const Eigen::Vector3d& vi, const Eigen::Vector3d& n,
                                double area) const {
  const double q = 0.5 * spec_.fluid_density * spec_.cd * area;
  const double vn = vi.dot(n);
  if (spec_.speed == DragSpeed::Normal)
    return -(q * std::abs(vn) * vn) * n;
  const double sign = vn > 0 ? 1.0 : vn < 0 ? -1.0 : 0.0;
  // q |v|^2 as each model has always formed it (the same bits for today's cases).
  if (spec_.geometry == Geometry::Reference) {
    const double s = vi.norm();
    return -(q * s * s * sign) * n;
  }
  return -(q * vi.squaredNorm() * sign) * n;
}

void Drag::add(const LoadTime&, const Mesh& mesh, const Eigen::VectorXd& u,
               const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  if (spec_.normal == DragNormal::Element)
    addElement(mesh, u, v, f);
  else
    addNodal(mesh, u, v, f);
}

void Drag::addNodal(const Mesh& mesh, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                    Eigen::VectorXd& f) const {
  const int n = mesh.numNodes();
  const bool current = spec_.geometry == Geometry::Current;
  // Current geometry: area vectors (sum of A_e n_e / 3) and tributary areas now.
  std::vector<Eigen::Vector3d> an;
  std::vector<double> area;
  if (current) {
    an.assign(static_cast<size_t>(n), Eigen::Vector3d::Zero());
    area.assign(static_cast<size_t>(n), 0.0);
    for (int e : elements_) {
      const Eigen::Vector3d ae = thirdAreaVector(mesh, e, u);
      const double third = ae.norm();
      for (int i : mesh.triangles[e]) {
        an[static_cast<size_t>(i)] += ae;
        area[static_cast<size_t>(i)] += third;
      }
    }
  }
  const bool reference_area = !current || spec_.area == DragArea::Reference;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    const Eigen::Vector3d& sum = current ? an[k] : node_normal_[k];
    if (!(node_area_[k] > 0) || !(sum.norm() > 0))
      continue; // not in the region
    const Eigen::Vector3d nrm = sum.normalized();
    f.segment<3>(3 * i) +=
        nodeForce(v.segment<3>(3 * i), nrm, reference_area ? node_area_[k] : area[k]);
  }
}

void Drag::addElement(const Mesh& mesh, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                      Eigen::VectorXd& f) const {
  // The drag paper's section 3.2: one frame per element, a load per element node.
  const bool current = spec_.geometry == Geometry::Current;
  const bool reference_area = !current || spec_.area == DragArea::Reference;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const int e = elements_[k];
    const Eigen::Vector3d ae = thirdAreaVector(mesh, e, current ? u : Eigen::VectorXd());
    if (!(ae.norm() > 0))
      continue; // a collapsed triangle has no normal
    const Eigen::Vector3d ne = ae.normalized();
    const double share = reference_area ? element_third_[k] : ae.norm();
    for (int i : mesh.triangles[e])
      f.segment<3>(3 * i) += nodeForce(v.segment<3>(3 * i), ne, share);
  }
}

} // namespace lamina::membrane
