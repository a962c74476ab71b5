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
  /// Adds the nodal forces (N) at time @p t, displacements @p u and
  /// velocities @p v of @p mesh (current position x = X + u) to @p f.
  virtual void add(double t, const Mesh& mesh, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                   Eigen::VectorXd& f) const = 0;
};

} // namespace lamina::membrane
