#include "membrane/loads/blast_pressure.hpp"

#include <algorithm>
#include <limits>

namespace lamina::membrane {

BlastPressure::BlastPressure(std::string name, std::vector<int> elements, const Mesh& mesh,
                             const BlastCharge& charge, Geometry geometry)
    : ElementPressure(std::move(name), std::move(elements), geometry), charge_(charge) {
  histories_.resize(static_cast<std::size_t>(mesh.numElements()));
  for (const int e : this->elements()) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(e)];
    const Eigen::Vector3d c = (mesh.point(tri[0]) + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
    try {
      histories_[static_cast<std::size_t>(e)] = charge.historyAt(c);
    } catch (const Error& err) {
      throw Error("blast on element " + std::to_string(mesh.elementLabel(e)) + ": " +
                  err.message());
    }
  }
}

BlastPressure::BlastPressure(std::string name, std::vector<int> elements, PressureTable table,
                             Geometry geometry)
    : ElementPressure(std::move(name), std::move(elements), geometry), table_(std::move(table)) {}

double BlastPressure::pressure(int e, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                               const LoadTime& when) const {
  // The mean over the step's interval (LoadTime): a pulse shorter than the
  // step delivers its impulse, in closed form (Friedlander) or piecewise
  // linear (a table).
  if (table_)
    return when.mean(table_->impulseBetween(when.from, when.to), table_->pressure(when.t));
  const BlastHistory& h = histories_[static_cast<std::size_t>(e)];
  if (when.to < h.arrival || when.from > h.arrival + h.incident.duration)
    return 0.0;
  const Eigen::Vector3d d = charge_->position - x;
  const double r = d.norm();
  const double cos_a = r > 0 ? n.dot(d) / r : 1.0;
  const double c = std::abs(cos_a);
  return (cos_a >= 0 ? -1.0 : 1.0) *
         when.mean(h.impulseBetween(when.from, when.to, c), h.pressure(when.t, c));
}

double BlastPressure::firstArrival() const {
  if (table_)
    return table_->times().front();
  double t = std::numeric_limits<double>::infinity();
  for (const int e : elements())
    t = std::min(t, histories_[static_cast<std::size_t>(e)].arrival);
  return t;
}

double BlastPressure::shortestPhase() const {
  if (table_)
    return table_->times().back() - table_->times().front();
  double d = std::numeric_limits<double>::infinity();
  for (const int e : elements())
    d = std::min(d, histories_[static_cast<std::size_t>(e)].incident.duration);
  return d;
}

double BlastPressure::lastEnd() const {
  if (table_)
    return table_->times().back();
  double t = 0;
  for (const int e : elements()) {
    const auto& h = histories_[static_cast<std::size_t>(e)];
    t = std::max(t, h.arrival + h.incident.duration);
  }
  return t;
}

} // namespace lamina::membrane
