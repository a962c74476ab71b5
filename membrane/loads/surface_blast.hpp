#pragma once
/// @file surface_blast.hpp
/// @brief Follower pressure on triangles in 3D: an air blast from a charge
/// (Kingery-Bulmash + Friedlander, combined over the angle of incidence) or
/// a user pressure history, acting along each triangle's current normal on
/// its current area.
///
/// Per triangle, with current nodes a, b, c: 2 A n = (b - a) x (c - a). For a
/// blast, d is the unit vector from the current centroid to the charge,
/// cos a = |n . d| (the face that sees the charge), and the force
/// F = -P(t, cos a) A sign(n . d) n pushes that face away from the charge;
/// a third of F goes to each node (exact for a uniform pressure on a linear
/// triangle). The blast parameters (arrival, peaks, duration, decays) are
/// evaluated once, at each triangle's reference centroid: the structure
/// moves little during the positive phase (milliseconds). For a table the
/// pressure acts along +n (the node order's normal), as the flat model's
/// `pressure` load acts along +z.

#include "membrane/loads/blast.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace lamina::membrane {

/// A pressure that follows the surface, on a set of triangles.
class SurfaceBlast {
public:
  /// A blast from @p charge on @p triangles of a mesh with reference nodes
  /// @p X0 (blast parameters evaluated at the reference centroids: an Error
  /// names the triangle whose scaled distance is outside the fits).
  SurfaceBlast(const BlastCharge& charge, std::vector<std::array<int, 3>> triangles,
               const std::vector<Eigen::Vector3d>& X0);

  /// A user pressure history @p table on @p triangles, along +n.
  SurfaceBlast(PressureTable table, std::vector<std::array<int, 3>> triangles);

  /// Adds the nodal forces at time @p t (s) for the current nodes
  /// x_i = X0_i + u_{3i..3i+2} to @p f (N, length 3 * nodes).
  void addForces(double t, const std::vector<Eigen::Vector3d>& X0, const Eigen::VectorXd& u,
                 Eigen::VectorXd& f) const;

  /// @return the earliest arrival time over the triangles (s; table: its first time)
  double firstArrival() const;
  /// @return the latest end of the positive phase over the triangles (s;
  /// table: its last time): after it the load is zero
  double lastEnd() const;
  /// @return the blast history of triangle @p k (empty for a table)
  const BlastHistory* history(int k) const;
  /// @return the number of loaded triangles
  int size() const { return static_cast<int>(triangles_.size()); }

private:
  std::vector<std::array<int, 3>> triangles_;
  std::optional<BlastCharge> charge_;
  std::vector<BlastHistory> histories_; ///< one per triangle (blast only)
  std::optional<PressureTable> table_;
};

} // namespace lamina::membrane
