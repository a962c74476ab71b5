#pragma once
/// @file rigid_surface.hpp
/// @brief The geometry of a rigid body the membrane can rest on (case
/// table `[[rigid_surface]]`): its signed distance and outward normal at a
/// point, per shape. The penalty forces, the motion and the bookkeeping are
/// contact.hpp's.
///
/// Shapes (the solid is the side a node must not enter):
/// - cylinder: the points within `radius` R of an infinite axis (a point
///   `center` c on it, unit direction `axis` a). Solid: r <= R, with
///   r = |(x - c) - ((x - c).a) a|; gap r - R, normal the radial direction.
/// - arc: a curved beam, the circular arc of radius R about the axis
///   (c, a), of `width` w along the axis (the flange the fabric lies on) and
///   radial `depth` d. Its solid is the ring of rectangular cross-section
///   { |s| <= w / 2, R - d <= r <= R }, s = (x - c).a: the rectangle
///   [-w/2, w/2] x [R - d, R] of the meridional (s, r) half-plane swept
///   about the axis. The fabric rests on its outer face r = R (the beam's
///   top: the drag paper's beams, 12 m radius, section 5.1). A solid of
///   revolution's distance is the distance in the meridional half-plane,
///   so the signed distance is that of the rectangle in (s, r), exact, and
///   the normal is +-a (the sides) or +-radial (outer, inner face). The
///   ring is whole (360 degrees): a roof's fabric reaches only its top.
/// - plane: a point p and a unit `normal` n pointing out of the solid
///   (towards the membrane). Solid: (x - p).n < 0; gap (x - p).n, normal n.
/// - sphere: the ball of `radius` R about `center` c. Solid: |x - c| <= R;
///   gap |x - c| - R, normal (x - c) / |x - c|.

#include "core/enum_names.hpp"

#include <Eigen/Dense>

#include <limits>

namespace lamina::membrane {

/// The shape of a rigid surface (key `shape` of `[[rigid_surface]]`).
enum class SurfaceShape {
  Cylinder, ///< infinite circular cylinder, solid inside
  Arc,      ///< curved beam: a ring of rectangular section (width x depth), radius to its top
  Plane,    ///< half-space, solid opposite the normal
  Sphere    ///< ball
};
/// The case-file names of SurfaceShape.
inline constexpr auto kSurfaceShapeNames =
    core::enumNames<SurfaceShape>({{"cylinder", SurfaceShape::Cylinder},
                                   {"arc", SurfaceShape::Arc},
                                   {"plane", SurfaceShape::Plane},
                                   {"sphere", SurfaceShape::Sphere}});

/// Where a point is relative to a solid.
struct Proximity {
  double gap = std::numeric_limits<double>::infinity(); ///< signed distance (m; < 0 inside)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    ///< outward unit normal of the nearest face
};

/// The geometry of one rigid surface at its initial position.
struct RigidSurface {
  SurfaceShape shape = SurfaceShape::Plane;          ///< which shape
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< centre (on the axis) or plane point (m)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();   ///< unit axis (cylinder, arc)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< unit outward normal (plane)
  double radius = 0; ///< m (cylinder, sphere; arc: to the outer face)
  double width = 0;  ///< m, along the axis (arc)
  double depth = 0;  ///< m, radial (arc)

  /// @return the gap and normal at point @p x (m), the surface at its initial position
  Proximity proximity(const Eigen::Vector3d& x) const;
  /// @return the thinnest extent of the solid (m): min(width, depth) for an
  /// arc, 2 R for a cylinder or sphere, infinity for a plane; a node deeper
  /// than half of it leaves by the opposite face
  double thickness() const;
};

} // namespace lamina::membrane
