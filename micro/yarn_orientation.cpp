#include "micro/yarn_orientation.hpp"

#include "micro/voxel_grid.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::micro {

double yarnCrimpAngle(const Inclusion& inc, const Eigen::Vector3d& p, const Eigen::Vector3d& L) {
  // the path normal at the foot is (-A k cos(k x_f), 1) / norm in the
  // (axis, crimp) plane: the tangent (1, A k cos(k x_f)) / norm is normal to it
  const YarnFrame f = yarnFrame(inc, nearestImage(p - inc.center, L));
  return std::atan2(-f.normal[inc.axis], f.normal[inc.crimp]);
}

OrientedVoxel yarnRotation(const Inclusion& inc, double theta) {
  OrientedVoxel o;
  o.axis = 3 - inc.axis - inc.crimp;
  // s = e_c . (e_w x e_a): +1 when (w, a, c) is a cyclic order of (x, y, z)
  const bool cyclic = (o.axis + 1) % 3 == inc.axis;
  o.angle = cyclic ? theta : -theta;
  return o;
}

bool followsPath(const Inclusion& inc, const std::vector<bool>& anisotropic) {
  return inc.shape == Shape::Yarn && inc.follow_path && inc.amplitude > 0 &&
         anisotropic[static_cast<std::size_t>(inc.phase)];
}

std::vector<OrientedVoxel> orientYarnVoxels(const std::vector<Inclusion>& inclusions,
                                            const std::vector<bool>& anisotropic,
                                            const std::array<int, 3>& n,
                                            const Eigen::Vector3d& size,
                                            const std::vector<std::int32_t>& phase,
                                            const std::vector<CompositeVoxel>& composites) {
  const Eigen::Vector3d h(size[0] / n[0], size[1] / n[1], size[2] / n[2]);
  auto oriented = [&](const Inclusion& inc, std::size_t idx) {
    OrientedVoxel o = yarnRotation(inc, yarnCrimpAngle(inc, voxelCentre(idx, n, h), size));
    o.index = idx;
    o.phase = inc.phase;
    return o;
  };
  std::vector<OrientedVoxel> out;
  // the yarn side of composite voxels: the yarn whose interface they carry
  for (const CompositeVoxel& c : composites)
    if (c.inclusion >= 0 &&
        followsPath(inclusions[static_cast<std::size_t>(c.inclusion)], anisotropic))
      out.push_back(oriented(inclusions[static_cast<std::size_t>(c.inclusion)], c.index));
  // whole voxels: centre inside the yarn (inclusions never overlap, so each
  // voxel is found once), composite voxels left to their laminate
  for (const Inclusion& inc : inclusions) {
    if (!followsPath(inc, anisotropic))
      continue;
    forEachVoxelInside(inc, n, size, [&](std::size_t idx) {
      if (phase[idx] != inc.phase || findVoxel(composites, idx))
        return;
      const OrientedVoxel o = oriented(inc, idx);
#pragma omp critical(lamina_oriented_voxels)
      out.push_back(o);
    });
  }
  std::sort(out.begin(), out.end(),
            [](const OrientedVoxel& a, const OrientedVoxel& b) { return a.index < b.index; });
  return out;
}

} // namespace lamina::micro
