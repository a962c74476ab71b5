#include "membrane/loads/surface_blast.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>

namespace lamina::membrane {

namespace {
Eigen::Vector3d current(const std::vector<Eigen::Vector3d>& X0, const Eigen::VectorXd& u, int i) {
  return X0[static_cast<std::size_t>(i)] + u.segment<3>(3 * i);
}
} // namespace

SurfaceBlast::SurfaceBlast(const BlastCharge& charge, std::vector<std::array<int, 3>> triangles,
                           const std::vector<Eigen::Vector3d>& X0)
    : triangles_(std::move(triangles)), charge_(charge) {
  histories_.reserve(triangles_.size());
  for (std::size_t k = 0; k < triangles_.size(); ++k) {
    const auto& t = triangles_[k];
    const Eigen::Vector3d c =
        (X0[static_cast<std::size_t>(t[0])] + X0[static_cast<std::size_t>(t[1])] +
         X0[static_cast<std::size_t>(t[2])]) /
        3.0;
    try {
      histories_.push_back(charge.historyAt(c));
    } catch (const Error& e) {
      throw Error("blast on element " + std::to_string(k) + ": " + e.message());
    }
  }
}

SurfaceBlast::SurfaceBlast(PressureTable table, std::vector<std::array<int, 3>> triangles)
    : triangles_(std::move(triangles)), table_(std::move(table)) {}

void SurfaceBlast::addForces(double t, const std::vector<Eigen::Vector3d>& X0,
                             const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  const double table_p = table_ ? table_->pressure(t) : 0.0;
  if (table_ && table_p == 0.0)
    return;
  for (std::size_t k = 0; k < triangles_.size(); ++k) {
    const auto& tri = triangles_[k];
    const Eigen::Vector3d a = current(X0, u, tri[0]);
    const Eigen::Vector3d b = current(X0, u, tri[1]);
    const Eigen::Vector3d c = current(X0, u, tri[2]);
    const Eigen::Vector3d n2A = (b - a).cross(c - a); // 2 A n
    Eigen::Vector3d force;                            // on the triangle, N
    if (table_) {
      force = 0.5 * table_p * n2A;
    } else {
      const BlastHistory& h = histories_[k];
      const double tau = t - h.arrival;
      if (tau < 0 || tau > h.incident.duration)
        continue;
      const Eigen::Vector3d to_charge = charge_->position - (a + b + c) / 3.0;
      const double norm = n2A.norm() * to_charge.norm();
      const double dot = n2A.dot(to_charge);
      const double cos_a = norm > 0 ? std::abs(dot) / norm : 0.0;
      const double p = h.pressure(t, cos_a);
      force = (dot >= 0 ? -0.5 : 0.5) * p * n2A; // pushes the seen face away
    }
    for (const int i : tri)
      f.segment<3>(3 * i) += force / 3.0;
  }
}

double SurfaceBlast::firstArrival() const {
  if (table_)
    return table_->times().front();
  double t = std::numeric_limits<double>::infinity();
  for (const auto& h : histories_)
    t = std::min(t, h.arrival);
  return t;
}

double SurfaceBlast::lastEnd() const {
  if (table_)
    return table_->times().back();
  double t = 0;
  for (const auto& h : histories_)
    t = std::max(t, h.arrival + h.incident.duration);
  return t;
}

const BlastHistory* SurfaceBlast::history(int k) const {
  return histories_.empty() ? nullptr : &histories_[static_cast<std::size_t>(k)];
}

} // namespace lamina::membrane
