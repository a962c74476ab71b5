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
/// integers h, k, l: normal to a coordinate axis in the simplest case) and
/// yarn (a woven yarn: an elliptic cross-section of width w and thickness t
/// swept in the normal plane along the periodic centre line
/// x_c = c_c + A sin(2 pi (x_a - c_a) / lambda), x_a running along the
/// cell axis `axis`, x_c the crimp axis `crimp`; see yarnFrame()).
/// Lengths are in the units of the cell size. Positions are periodic:
/// distances use the nearest image.

#include "core/enum_names.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace lamina::micro {

/// Kinds of inclusion.
enum class Shape { Sphere, Ellipsoid, Fiber, Layer, Yarn };

/// The cell-file names of Shape (`shape` of an [[inclusions]] table).
inline constexpr auto kShapeNames = core::enumNames<Shape>({{"sphere", Shape::Sphere},
                                                            {"ellipsoid", Shape::Ellipsoid},
                                                            {"fiber", Shape::Fiber},
                                                            {"layer", Shape::Layer},
                                                            {"yarn", Shape::Yarn}});

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
  double thickness = 0; ///< layer thickness; yarn: cross-section extent along the path normal
  double width = 0; ///< yarn: cross-section extent along the third axis (neither axis nor crimp)
  double amplitude = 0;  ///< yarn: amplitude A of the centre line's sinusoid (0: straight)
  double wavelength = 0; ///< yarn: period lambda of the centre line (divides the cell length)
  int crimp = 2;         ///< yarn: the axis the centre line undulates along (not `axis`)
  /// yarn: its phase's law follows the centre line (rotated per voxel to
  /// the tangent; yarn_orientation.hpp)
  bool follow_path = true;
  int axis = 0; ///< fiber/yarn direction, layer normal (0=x,1=y,2=z), -1 if oblique
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
  /// @return fiber: the offsets of @p p from every periodic copy of the axis
  /// that passes within @p R of it (perpendicular to the axis; exact)
  std::vector<Eigen::Vector3d> axisOffsetsWithin(const Eigen::Vector3d& p, double R,
                                                 const Eigen::Vector3d& L) const;
  /// @return oblique fiber: the distance between neighbouring parallel
  /// copies (the fiber must be thinner); oblique layer: the plane spacing
  double periodicSpacing(const Eigen::Vector3d& L) const;

  /// @return whether @p p (cell coordinates) lies inside, using the nearest
  /// periodic image of p - center in a cell of size @p L
  bool contains(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const;
  /// @return whether the point at offset @p d from the centre lies inside,
  /// @p d being the nearest periodic image (contains() is this test of
  /// nearestImage(p - center, L))
  bool containsOffset(const Eigen::Vector3d& d, const Eigen::Vector3d& L) const;
  /// @return the inclusion's volume (fiber and layer: inside one cell of size @p L)
  double volume(const Eigen::Vector3d& L) const;
  /// @return half the extent of the inclusion along each cell axis
  /// (fiber/layer: half the cell length along the unbounded directions)
  Eigen::Vector3d halfExtent(const Eigen::Vector3d& L) const;
  /// Scales all lengths (semi-axes, radius, thickness) by @p s; a yarn
  /// scales its cross-section (width, thickness) and keeps its centre line.
  void scale(double s);
  /// @return the exponent d with volume ~ length^d (3, fiber and yarn 2, layer 1)
  int dimension() const;

  /// @return yarn: the length of its centre line inside one cell of size
  /// @p L (L_axis / lambda periods, each integrated by the trapezoid rule,
  /// spectrally accurate for the periodic integrand)
  double pathLength(const Eigen::Vector3d& L) const;
  /// @return yarn: the smallest radius of curvature of its centre line,
  /// 1 / (A k^2) with k = 2 pi / lambda (infinite when straight)
  double minCurvatureRadius() const;
};

/// Coordinates of a point relative to a yarn's swept cross-section.
struct YarnFrame {
  double u = 0;                                     ///< offset along the width axis
  double v = 0;                                     ///< signed offset along the path normal
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(); ///< unit path normal (in the axis-crimp plane)
  int width_axis = 1;                               ///< the axis neither `axis` nor `crimp`
};

/// @return the cross-section coordinates of @p d (the nearest image of a
/// point minus the yarn's centre) for the yarn @p inc: the foot is the
/// nearest point of the centre line in the axis-crimp plane (searched on
/// [s - t/2, s + t/2], the only feet a point of the yarn can have), u the
/// offset along the width axis, v the offset along the normal there. The
/// point is inside iff (u / (w/2))^2 + (v / (t/2))^2 <= 1 (exact while t/2
/// is below the smallest radius of curvature, checked at placement).
YarnFrame yarnFrame(const Inclusion& inc, const Eigen::Vector3d& d);

/// @return the nearest periodic image of @p d in a cell of size @p L
Eigen::Vector3d nearestImage(Eigen::Vector3d d, const Eigen::Vector3d& L);

/// @return whether @p a and @p b, each grown by @p gap / 2, overlap in the
/// periodic cell of size @p L. Ellipsoid pairs use the Perram-Wertheim
/// contact function (exact); fibers and layers exact; two yarns: a point of
/// either surface inside the other (sampled, 512 x 48 points per yarn);
/// mixed pairs with a fiber, layer or yarn use a conservative bounding test.
bool overlaps(const Inclusion& a, const Inclusion& b, double gap, const Eigen::Vector3d& L);

} // namespace lamina::micro
