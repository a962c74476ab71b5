#pragma once
/// @file element_pressure.hpp
/// @brief Pressure on elements along their current normal, on their current
/// area: node a of element e gets p_e A_e n_e / 3 (exact for a pressure
/// constant over the element), i.e. p_e (x2 - x1) x (x3 - x1) / 6. The
/// normal follows the triangle's node order (+z for a flat mesh).
///
/// A pressure law p(x, n, t) (uniform, blast, ...) derives from
/// ElementPressure and implements pressure().

#include "membrane/model/profile.hpp"
#include "membrane/loads/surface_load.hpp"

#include <vector>

namespace lamina::membrane {

/// Base class of follower pressures on a set of elements.
class ElementPressure : public SurfaceLoad {
public:
  /// Acts on @p elements (triangle indices of the mesh).
  ElementPressure(std::string name, std::vector<int> elements);
  WorkKind kind() const override { return WorkKind::External; }
  const std::string& name() const override { return name_; }
  void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
           const Eigen::VectorXd& v, Eigen::VectorXd& f) const override;

protected:
  /// @return the pressure (Pa, positive pushes along the normal) on element
  /// @p e with current centroid @p x and unit normal @p n at @p when (its
  /// mean over when's interval, LoadTime)
  virtual double pressure(int e, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                          const LoadTime& when) const = 0;

private:
  std::string name_;
  std::vector<int> elements_;
};

/// p = value * profile(t), the same on every element.
class UniformPressure final : public ElementPressure {
public:
  /// @p value in Pa.
  UniformPressure(std::string name, std::vector<int> elements, double value, TimeProfile profile);

protected:
  double pressure(int e, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                  const LoadTime& when) const override;

private:
  double value_;
  TimeProfile profile_;
};

} // namespace lamina::membrane
