#pragma once
/// @file inclusion.hpp
/// @brief Inclusion shapes of a periodic unit cell and their geometry:
/// membership of a point, volume, periodic overlap with a gap.
///
/// Shapes: sphere (an ellipsoid with equal semi-axes), ellipsoid (semi-axes
/// a, b, c along its own axes, rotated by R), fiber (infinite circular
/// cylinder along a lattice direction u L_x e_x + v L_y e_y + w L_z e_z with
/// integers u, v, w: periodic, a coordinate axis in the simplest case) and
/// layer (slab between the lattice planes h x/L_x + k y/L_y + l z/L_z = const,
/// integers h, k, l: normal to a coordinate axis in the simplest case).
/// Lengths are in the units of the cell size. Positions are periodic:
/// distances use the nearest image.

#include <Eigen/Dense>

#include <string>

namespace lamina::micro {

/// Kinds of inclusion.
enum class Shape { Sphere, Ellipsoid, Fiber, Layer };

/// @return the shape for "sphere", "ellipsoid", "fiber", "layer"; false if unknown
bool parseShape(const std::string& word, Shape& out);
/// @return the name of @p s
std::string toString(Shape s);

/// One placed inclusion.
struct Inclusion {
  Shape shape = Shape::Sphere;                      ///< geometric shape
  int phase = 0;                                    ///< phase index it is made of
  Eigen::Vector3d center = Eigen::Vector3d::Zero(); ///< centre (a point on the axis / mid-plane)
  Eigen::Vector3d semi = Eigen::Vector3d::Ones();   ///< ellipsoid semi-axes (sphere: r, r, r)
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< columns: the ellipsoid axes in cell axes
  double radius = 0;                                ///< fiber radius
  double thickness = 0;                             ///< layer thickness
  int axis = 0; ///< fiber direction / layer normal (0=x,1=y,2=z), -1 if oblique
  /// fiber: lattice direction [u, v, w]; layer: plane indices [h, k, l]
  /// (integers without a common factor; e_axis for an axis-aligned one)
  Eigen::Vector3i lattice = Eigen::Vector3i(1, 0, 0);

  /// Sets the direction (fiber) or plane indices (layer) to @p m (reduced by
  /// their greatest common divisor); axis-aligned ones set @p axis too.
  void setLattice(const Eigen::Vector3i& m);
  /// @return the unit fiber direction or layer normal in a cell of size @p L
  Eigen::Vector3d unitDirection(const Eigen::Vector3d& L) const;
  /// @return the unit outward normal of the surface near @p p (the gradient
  /// direction of the shape's defining function there)
  Eigen::Vector3d normalAt(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const;
  /// @return fiber: the offset of @p p from the nearest periodic copy of the
  /// axis (perpendicular to it; its norm is the distance to the axis)
  Eigen::Vector3d axisOffset(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const;
  /// @return oblique fiber: the distance between neighbouring parallel
  /// copies (the fiber must be thinner); oblique layer: the plane spacing
  double periodicSpacing(const Eigen::Vector3d& L) const;

  /// @return whether @p p (cell coordinates) lies inside, using the nearest
  /// periodic image of p - center in a cell of size @p L
  bool contains(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const;
  /// @return the inclusion's volume (fiber and layer: inside one cell of size @p L)
  double volume(const Eigen::Vector3d& L) const;
  /// @return half the extent of the inclusion along each cell axis
  /// (fiber/layer: half the cell length along the unbounded directions)
  Eigen::Vector3d halfExtent(const Eigen::Vector3d& L) const;
  /// Scales all lengths (semi-axes, radius, thickness) by @p s.
  void scale(double s);
  /// @return the exponent d with volume ~ length^d (3, fiber 2, layer 1)
  int dimension() const;
};

/// @return the nearest periodic image of @p d in a cell of size @p L
Eigen::Vector3d nearestImage(Eigen::Vector3d d, const Eigen::Vector3d& L);

/// @return whether @p a and @p b, each grown by @p gap / 2, overlap in the
/// periodic cell of size @p L. Ellipsoid pairs use the Perram-Wertheim
/// contact function (exact); fibers and layers exact; mixed pairs with a
/// fiber or layer use a conservative bounding test.
bool overlaps(const Inclusion& a, const Inclusion& b, double gap, const Eigen::Vector3d& L);

} // namespace lamina::micro
