#pragma once
/// @file inside_query.hpp
/// @brief An inclusion's inside test prepared for the millions of points of
/// a voxel grid (phase map, composite-voxel corners and sub-samples).
///
/// contains() gives Inclusion::contains's answer bit for bit: it forms the
/// same nearest-image offset (the same operations, with the image index
/// found by an inline rounding instead of std::round's library call) and
/// hands it to Inclusion::containsOffset; a point within 1e-9 of a cell of
/// the half-cell boundary, where the two roundings could differ, goes to
/// Inclusion::contains itself.
///
/// boxSide() decides whole boxes (voxels) far from the surface from one
/// evaluation at the box centre and a Lipschitz bound of the shape's
/// defining function, with a relative margin of kBoxMargin over the
/// round-off of both computations: sphere, ellipsoid and axis-aligned
/// fibre (|M d| <= 1 with M = diag(1 / semi) R^T, or the distance to the
/// axis over the radius: |M d| changes by at most |M| |delta| over an
/// offset delta) and
/// yarn (the cheap rejections and acceptance that open Inclusion::contains:
/// beyond the width or the crimp band, or within the section around the
/// centre-line point straight along the crimp axis, A sin(k x) being
/// A k-Lipschitz). Other shapes and boxes across the half-cell boundary
/// give "not known".

#include "micro/inclusion.hpp"

#include <Eigen/Dense>

namespace lamina::micro {

/// Relative margin of InsideQuery::boxSide over round-off.
inline constexpr double kBoxMargin = 1e-9;

/// Voxels per run tested at once by InsideQuery::runSide before voxel by voxel.
inline constexpr int kVoxelRun = 8;

/// An inclusion's inside test prepared for many points (see the file comment).
class InsideQuery {
public:
  /// Prepares the test of @p inc (kept by reference) in a cell of size @p L.
  InsideQuery(const Inclusion& inc, const Eigen::Vector3d& L);

  /// @return inc.contains(@p p, L), bit for bit
  bool contains(const Eigen::Vector3d& p) const;

  /// @return +1 when contains() holds at every point of the box of centre
  /// @p p and half edges @p half, -1 when it holds at none of them, 0 when
  /// not known (the box may be cut by the surface)
  int boxSide(const Eigen::Vector3d& p, const Eigen::Vector3d& half) const;

  /// @return boxSide() of the run of voxels (@p i, @p j, @p k0 .. @p k1)
  /// of a grid of voxel edges @p h (voxel (i, j, k) spans [i h_x, (i+1) h_x]
  /// x ...): whole runs inside or outside are skipped at once
  int runSide(int i, int j, int k0, int k1, const Eigen::Vector3d& h) const;

  /// Sphere, ellipsoid and axis-aligned fibre: the shape is |M d|^2 <= 1
  /// for the offset d from the centre (M = form()). Sets @p m0 to M d at
  /// @p p when every point of the box (@p p, @p half) lies within one
  /// periodic image; then |m0 + M (x - p)|^2 approximates the exact test's
  /// value at x to far below kBoxMargin. @return false otherwise (other
  /// shapes, or the box across a half-cell boundary)
  bool quadraticForm(const Eigen::Vector3d& p, const Eigen::Vector3d& half,
                     Eigen::Vector3d& m0) const;
  /// @return M of quadraticForm()
  const Eigen::Matrix3d& form() const { return M_; }

private:
  /// Forms the nearest-image offset @p d of every point of the box (@p p,
  /// @p half) as nearestImage does; false when the box comes within 1e-9 of
  /// a cell of a half-cell boundary along a component the shape reads.
  bool offset(const Eigen::Vector3d& p, const Eigen::Vector3d& half, Eigen::Vector3d& d) const;

  const Inclusion& inc_;
  Eigen::Vector3d L_, invL_;
  bool reads_[3] = {true, true, true}; ///< components of the offset the shape reads
  bool quadratic_ = false;             ///< ellipsoid or axis-aligned fibre within round-off bounds
  Eigen::Matrix3d M_ = Eigen::Matrix3d::Zero(); ///< quadratic: the shape is |M d|^2 <= 1
  double normM_ = 0;                            ///< quadratic: the spectral norm of M
};

} // namespace lamina::micro
