#include "membrane/loads/element_pressure.hpp"

#include "membrane/loads/traction.hpp"

namespace lamina::membrane {

ElementPressure::ElementPressure(std::string name, std::vector<int> elements, Geometry geometry)
    : name_(std::move(name)), elements_(std::move(elements)), geometry_(geometry) {}

void ElementPressure::add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
                          const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  (void)v;
  const bool current = geometry_ == Geometry::Current;
  for (int e : elements_) {
    const auto& tri = mesh.triangles[e];
    std::array<Eigen::Vector3d, 3> x;
    for (int a = 0; a < 3; ++a)
      x[a] = current ? Eigen::Vector3d(mesh.point(tri[a]) + u.segment<3>(3 * tri[a]))
                     : mesh.point(tri[a]);
    // A n: the current area vector, or the reference area along e_z.
    const Eigen::Vector3d an = current ? Eigen::Vector3d(0.5 * (x[1] - x[0]).cross(x[2] - x[0]))
                                       : Eigen::Vector3d(0, 0, mesh.area(e));
    const double A = an.norm();
    if (!(A > 0))
      continue;
    const double p = pressure(e, (x[0] + x[1] + x[2]) / 3.0, an / A, when);
    for (int a = 0; a < 3; ++a)
      f.segment<3>(3 * tri[a]) += (p / 3.0) * an;
  }
}

UniformPressure::UniformPressure(std::string name, const Mesh& mesh, std::vector<int> elements,
                                 double value, TimeProfile profile, Geometry geometry)
    : ElementPressure(std::move(name), std::move(elements), geometry), value_(value),
      profile_(std::move(profile)) {
  if (geometry == Geometry::Reference) {
    pattern_ = Eigen::VectorXd::Zero(3 * mesh.numNodes());
    addTraction(
        mesh, this->elements(), Eigen::Vector3d::UnitZ(),
        [this](const Eigen::Vector2d&) { return value_; }, pattern_);
  }
}

double UniformPressure::factor(const LoadTime& when) const {
  return when.mean(profile_.integral(when.from, when.to), profile_(when.t));
}

void UniformPressure::add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
                          const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  if (geometry() == Geometry::Current) {
    ElementPressure::add(when, mesh, u, v, f);
    return;
  }
  // The fixed pattern times the profile (the same force as the element loop).
  if (const double s = factor(when); s != 0)
    f += s * pattern_;
}

double UniformPressure::pressure(int, const Eigen::Vector3d&, const Eigen::Vector3d&,
                                 const LoadTime& when) const {
  return value_ * factor(when);
}

} // namespace lamina::membrane
