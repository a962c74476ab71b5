#pragma once
/// @file yarn_orientation.hpp
/// @brief A woven yarn's law follows its centre line: the phase's stiffness
/// is rotated, voxel by voxel, from the yarn's `direction` axis to the
/// tangent of the centre line at the voxel centre's foot point.
///
/// Model (docs/homogenize.md, "Yarn law along the path"): the phase's C is
/// given in cell axes with its fibre axis along the yarn's `direction` e_a.
/// The centre line x_c = A sin(k x_a) (relative to the yarn's centre, crimp
/// axis c, k = 2 pi / lambda) has at the foot x_f of a point (yarnFrame())
/// the tangent e_a cos(theta) + e_c sin(theta) with the crimp angle
///   theta = atan(A k cos(k x_f)).
/// The rotation taking e_a to that tangent is a right-handed rotation about
/// the width axis e_w by phi = s theta, s = e_c . (e_w x e_a) = +-1; the
/// voxel's stiffness is C.rotated(axisRotation(w, phi)) (materials'
/// rotation, C'_ijkl = R_ip R_jq R_kr R_ls C_pqrs).
///
/// Which voxels: every voxel whose centre lies in a yarn with `follow_path`
/// (whole yarn voxels), and the yarn side of every composite voxel whose
/// interface comes from such a yarn (the laminate takes the rotated C of
/// the yarn phase), both with the foot of the voxel centre. Yarns of an
/// isotropic phase are skipped (a rotation leaves an isotropic C as it is:
/// no per-voxel entries), as are straight yarns (A = 0: theta = 0, the
/// result is the unrotated one bit for bit).

#include "micro/inclusion.hpp"
#include "micro/voxel_cell.hpp"

#include <Eigen/Dense>

#include <array>
#include <cstdint>
#include <vector>

namespace lamina::micro {

/// @return the crimp angle theta = atan(A k cos(k x_f)) (radians) of the
/// yarn @p inc's centre line at the foot x_f of the point @p p (cell
/// coordinates, nearest image in a cell of size @p L)
double yarnCrimpAngle(const Inclusion& inc, const Eigen::Vector3d& p, const Eigen::Vector3d& L);

/// @return the OrientedVoxel rotation (axis, signed angle phi) that takes
/// the yarn @p inc's direction to its tangent at crimp angle @p theta
OrientedVoxel yarnRotation(const Inclusion& inc, double theta);

/// @return whether the yarn @p inc rotates its phase along the path: a yarn
/// with follow_path, a non-zero amplitude and a phase marked in
/// @p anisotropic (indexed by phase)
bool followsPath(const Inclusion& inc, const std::vector<bool>& anisotropic);

/// @return the oriented voxels of the grid (@p n voxels, cell @p size), in
/// voxel order: centre inside a path-following yarn (phase map @p phase,
/// composite voxels @p composites excluded) or a composite voxel whose
/// interface is such a yarn's. @p anisotropic marks the phases to rotate.
std::vector<OrientedVoxel> orientYarnVoxels(const std::vector<Inclusion>& inclusions,
                                            const std::vector<bool>& anisotropic,
                                            const std::array<int, 3>& n,
                                            const Eigen::Vector3d& size,
                                            const std::vector<std::int32_t>& phase,
                                            const std::vector<CompositeVoxel>& composites);

} // namespace lamina::micro
