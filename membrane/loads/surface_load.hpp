#pragma once
/// @file surface_load.hpp
/// @brief A load that depends on the current configuration: it follows the
/// surface (pressure along the current normal on the current area, drag
/// with the current normals), or the displacement (springs to the ground).
///
/// A new kind is one class implementing add(); element pressures of any
/// p(x, n, t) derive from ElementPressure (element_pressure.hpp).

#include "membrane/model/mesh.hpp"

#include <Eigen/Dense>

#include <string>

namespace lamina::membrane {

/// When a load acts: the time t of the state it is evaluated at, and the
/// interval [from, to] around it that the force stands for in the time
/// step. A time-dependent load gives the mean of its value over the
/// interval (its impulse / (to - from)), so that a pulse shorter than the
/// step still delivers its impulse; over an empty interval (from = to = t)
/// it gives its value at t.
struct LoadTime {
  double t = 0;    ///< the state's time (s)
  double from = 0; ///< start of the interval (s), <= t
  double to = 0;   ///< end of the interval (s), >= t
  /// The instant @p instant (an empty interval): the load's value there.
  LoadTime(double instant) : t(instant), from(instant), to(instant) {} // NOLINT: implicit
  /// Time @p instant standing for the interval [@p start, @p end].
  LoadTime(double instant, double start, double end) : t(instant), from(start), to(end) {}
  /// @return the mean of a load whose integral over [from, to] is
  /// @p integral, or @p value (its value at t) when the interval is empty
  double mean(double integral, double value) const {
    return to > from ? integral / (to - from) : value;
  }
};

/// The configuration a surface load is evaluated on.
enum class Geometry {
  Reference, ///< the reference (initial) positions X: the linear model's
  Current    ///< the current positions x = X + u: the large-deflection model's
};

/// Which work a load's force enters in the energy bookkeeping.
enum class WorkKind {
  External, ///< external_work
  Drag,     ///< drag_work
  Spring,   ///< spring_work (its force is also a support reaction)
};

/// A configuration-dependent nodal force.
class SurfaceLoad {
public:
  virtual ~SurfaceLoad() = default;
  /// @return the work bucket of this load
  virtual WorkKind kind() const = 0;
  /// @return a name for messages and the reactions of springs
  virtual const std::string& name() const = 0;
  /// Adds the nodal forces (N) at time @p when (a time-dependent load:
  /// its mean over when's interval), displacements @p u and velocities
  /// @p v of @p mesh (current position x = X + u) to @p f.
  virtual void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
                   const Eigen::VectorXd& v, Eigen::VectorXd& f) const = 0;
};

} // namespace lamina::membrane
