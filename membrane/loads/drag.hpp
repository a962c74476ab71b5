#pragma once
/// @file drag.hpp
/// @brief The aerodynamic drag of the drag paper ("Drag force on fabric
/// roofs", eqs. 1-3): one load for both membrane models, on the reference
/// (flat, linear model) or the current (deformed) geometry.
///
/// At node i, with normal n, tributary area A and v_n = v_i . n:
///   'normal':    F = - 1/2 rho_f C_d A |v_n| v_n n
///   'resultant': F = - 1/2 rho_f C_d A |v_i|^2 sign(v_n) n
/// (eqs. 1-3 with V = |v_n| or |v_i|; along the normal, fluid pressure being
/// normal to the surface, opposite to the normal motion). Geometry: the
/// positions the normals and the current areas come from (Reference: X, the
/// linear model's flat membrane, normal e_z; Current: x = X + u). Area: the
/// tributary area of the geometry's triangles (a third of each, Current) or
/// the paper's constant one from the reference triangles (Reference; section
/// 3.2: "the tributary area A_i ... remains constant"). Normal: per node,
/// the normalized sum of its triangles' area vectors, with the node's whole
/// tributary area (Nodal); or the paper's section 3.2 form, per element e
/// and each of its nodes, the element's own normal n_e with the element's
/// share A_e / 3 (Element: the LS-DYNA loop of one local frame per element
/// and one load per element node).

#include "core/enum_names.hpp"
#include "membrane/loads/surface_load.hpp"

#include <vector>

namespace lamina::membrane {

/// The speed V of the drag paper's eq. (1) (key `velocity`).
enum class DragSpeed {
  Normal,   ///< V = |v_n|, the normal component ("normal", the default)
  Resultant ///< V = |v|, the whole velocity ("resultant")
};
/// The case-file names of DragSpeed.
inline constexpr auto kDragSpeedNames = core::enumNames<DragSpeed>(
    {{"normal", DragSpeed::Normal}, {"resultant", DragSpeed::Resultant}});

/// The tributary area of the drag (key `area`).
enum class DragArea {
  Current,  ///< a third of each triangle of the geometry in use ("current", the default)
  Reference ///< the paper's constant area, from the reference triangles ("reference")
};
/// The case-file names of DragArea.
inline constexpr auto kDragAreaNames =
    core::enumNames<DragArea>({{"current", DragArea::Current}, {"reference", DragArea::Reference}});

/// The normal of the drag (key `normal`).
enum class DragNormal {
  Nodal,  ///< per node, the normalized sum of its triangles' area vectors ("nodal", the default)
  Element ///< per element and node, the element's normal (the paper's 3.2; "element")
};
/// The case-file names of DragNormal.
inline constexpr auto kDragNormalNames =
    core::enumNames<DragNormal>({{"nodal", DragNormal::Nodal}, {"element", DragNormal::Element}});

/// What a drag region is: its coefficients and variants.
struct DragSpec {
  double cd = 1.0;                         ///< drag (or pressure) coefficient C_d
  double fluid_density = 1.225;            ///< rho_f (kg/m^3, air)
  DragSpeed speed = DragSpeed::Normal;     ///< V of eq. (1)
  Geometry geometry = Geometry::Reference; ///< positions of the normals and current areas
  DragArea area = DragArea::Current;       ///< tributary area
  DragNormal normal = DragNormal::Nodal;   ///< normal
};

/// Drag on a set of elements (see the file comment).
class Drag final : public SurfaceLoad {
public:
  /// Drag @p spec on @p elements of @p mesh (the reference areas and, for
  /// the reference geometry, the normals are computed here).
  Drag(std::string name, const Mesh& mesh, std::vector<int> elements, const DragSpec& spec);
  WorkKind kind() const override { return WorkKind::Drag; }
  const std::string& name() const override { return name_; }
  void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
           const Eigen::VectorXd& v, Eigen::VectorXd& f) const override;
  /// @return the variants and coefficients
  const DragSpec& spec() const { return spec_; }

private:
  /// The element's area vector A_e n_e / 3 at displacements @p u (empty: reference).
  Eigen::Vector3d thirdAreaVector(const Mesh& mesh, int e, const Eigen::VectorXd& u) const;
  /// The drag at one node: velocity @p vi, unit normal @p n, tributary area @p area.
  Eigen::Vector3d nodeForce(const Eigen::Vector3d& vi, const Eigen::Vector3d& n, double area) const;
  void addNodal(const Mesh& mesh, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                Eigen::VectorXd& f) const;
  void addElement(const Mesh& mesh, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                  Eigen::VectorXd& f) const;
  std::string name_;
  std::vector<int> elements_;
  DragSpec spec_;
  std::vector<double> element_third_; ///< reference A_e / 3 per listed element
  std::vector<double> node_area_;     ///< reference tributary area per node (0: not in the set)
  std::vector<Eigen::Vector3d>
      node_normal_; ///< Reference geometry: the sum of area vectors per node
};

} // namespace lamina::membrane
