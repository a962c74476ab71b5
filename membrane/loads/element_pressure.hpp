#pragma once
/// @file element_pressure.hpp
/// @brief Pressure on elements, one load for both membrane models with a
/// Geometry flag:
/// - Current (the large-deflection model): along the element's current
///   normal on its current area, node a of element e gets p_e A_e n_e / 3
///   (exact for a pressure constant over the element), i.e.
///   p_e (x2 - x1) x (x3 - x1) / 6; the normal follows the triangle's node
///   order (+z for a flat mesh).
/// - Reference (the linear model): on the flat reference membrane, along
///   e_z on the reference area A_e (whatever the node order), node a gets
///   p_e A_e e_z / 3 at the reference centroid.
///
/// A pressure law p(x, n, t) (uniform, blast, ...) derives from
/// ElementPressure and implements pressure(). A uniform pressure on the
/// reference geometry is a fixed pattern times its time profile: it is
/// integrated once (traction.hpp) and scaled each step.

#include "membrane/loads/surface_load.hpp"
#include "membrane/model/profile.hpp"

#include <vector>

namespace lamina::membrane {

/// Base class of pressures on a set of elements.
class ElementPressure : public SurfaceLoad {
public:
  /// Acts on @p elements (triangle indices of the mesh) in @p geometry.
  ElementPressure(std::string name, std::vector<int> elements, Geometry geometry);
  WorkKind kind() const override { return WorkKind::External; }
  const std::string& name() const override { return name_; }
  void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
           const Eigen::VectorXd& v, Eigen::VectorXd& f) const override;
  /// @return the geometry the pressure acts on
  Geometry geometry() const { return geometry_; }

protected:
  /// @return the pressure (Pa, positive pushes along the normal) on element
  /// @p e with centroid @p x and unit normal @p n (current or reference) at
  /// @p when (its mean over when's interval, LoadTime)
  virtual double pressure(int e, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                          const LoadTime& when) const = 0;
  /// @return the elements
  const std::vector<int>& elements() const { return elements_; }

private:
  std::string name_;
  std::vector<int> elements_;
  Geometry geometry_;
};

/// p = value * profile(t), the same on every element.
class UniformPressure final : public ElementPressure {
public:
  /// @p value in Pa on @p elements of @p mesh in @p geometry.
  UniformPressure(std::string name, const Mesh& mesh, std::vector<int> elements, double value,
                  TimeProfile profile, Geometry geometry);
  void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
           const Eigen::VectorXd& v, Eigen::VectorXd& f) const override;

protected:
  double pressure(int e, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                  const LoadTime& when) const override;

private:
  /// @return the profile's mean over when's interval (LoadTime)
  double factor(const LoadTime& when) const;
  double value_;
  TimeProfile profile_;
  Eigen::VectorXd pattern_; ///< Reference: the nodal forces at profile 1 (N)
};

} // namespace lamina::membrane
