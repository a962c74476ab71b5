#include "membrane/loads/element_pressure.hpp"

namespace lamina::membrane {

ElementPressure::ElementPressure(std::string name, std::vector<int> elements)
    : name_(std::move(name)), elements_(std::move(elements)) {}

void ElementPressure::add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
                          const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  (void)v;
  for (int e : elements_) {
    const auto& tri = mesh.triangles[e];
    std::array<Eigen::Vector3d, 3> x;
    for (int a = 0; a < 3; ++a)
      x[a] = mesh.point(tri[a]) + u.segment<3>(3 * tri[a]);
    const Eigen::Vector3d an = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]); // A n
    const double A = an.norm();
    if (!(A > 0))
      continue;
    const double p = pressure(e, (x[0] + x[1] + x[2]) / 3.0, an / A, when);
    for (int a = 0; a < 3; ++a)
      f.segment<3>(3 * tri[a]) += (p / 3.0) * an;
  }
}

UniformPressure::UniformPressure(std::string name, std::vector<int> elements, double value,
                                 TimeProfile profile)
    : ElementPressure(std::move(name), std::move(elements)), value_(value),
      profile_(std::move(profile)) {}

double UniformPressure::pressure(int, const Eigen::Vector3d&, const Eigen::Vector3d&,
                                 const LoadTime& when) const {
  return value_ * when.mean(profile_.integral(when.from, when.to), profile_(when.t));
}

} // namespace lamina::membrane
