#include "micro/voxel_grid.hpp"

#include "core/parallel.hpp"
#include "micro/inside_query.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::micro {

void voxelRange(const Inclusion& inc, const std::array<int, 3>& n, const Eigen::Vector3d& size,
                std::array<int, 3>& lo, std::array<int, 3>& hi) {
  // bounding box of voxel indices around the centre, wrapped periodically
  const Eigen::Vector3d e = inc.halfExtent(size);
  for (std::size_t d = 0; d < 3; ++d) {
    const double h = size[static_cast<int>(d)] / n[d];
    const double c = inc.center[static_cast<int>(d)], r = e[static_cast<int>(d)];
    if (2 * r >= size[static_cast<int>(d)]) {
      lo[d] = 0;
      hi[d] = n[d] - 1;
    } else {
      lo[d] = static_cast<int>(std::floor((c - r) / h - 0.5)) - 1;
      hi[d] = static_cast<int>(std::ceil((c + r) / h - 0.5)) + 1;
    }
    // never visit a voxel twice (threads write disjoint voxels)
    if (hi[d] - lo[d] + 1 >= n[d]) {
      lo[d] = 0;
      hi[d] = n[d] - 1;
    }
  }
}

void forEachVoxelInside(const Inclusion& inc, const std::array<int, 3>& n,
                        const Eigen::Vector3d& size,
                        const std::function<void(std::size_t)>& visit) {
  const Eigen::Vector3d h(size[0] / n[0], size[1] / n[1], size[2] / n[2]);
  const InsideQuery query(inc, size);
  std::array<int, 3> lo{}, hi{};
  voxelRange(inc, n, size, lo, hi);
  core::ParallelErrors errors; // visit may throw
#pragma omp parallel for schedule(static)
  for (int i = lo[0]; i <= hi[0]; ++i)
    errors.run([&] {
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int k0 = lo[2]; k0 <= hi[2]; k0 += kVoxelRun) {
          // a run of voxels wholly outside is skipped, wholly inside visited
          const int k1 = std::min(k0 + kVoxelRun - 1, hi[2]);
          const int run = query.runSide(i, j, k0, k1, h);
          if (run < 0)
            continue;
          for (int k = k0; k <= k1; ++k) {
            const Eigen::Vector3d p((i + 0.5) * h[0], (j + 0.5) * h[1], (k + 0.5) * h[2]);
            if (run > 0 || query.contains(p))
              visit(wrappedVoxelIndex(i, j, k, n));
          }
        }
    });
  errors.rethrow();
}

std::vector<std::int32_t> voxelize(const std::vector<Inclusion>& inclusions,
                                   const std::array<int, 3>& n, const Eigen::Vector3d& size) {
  const std::size_t total = static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
                            static_cast<std::size_t>(n[2]);
  std::vector<std::int32_t> map(total, 0);
  for (const Inclusion& inc : inclusions)
    forEachVoxelInside(inc, n, size, [&](std::size_t idx) { map[idx] = inc.phase; });
  return map;
}

} // namespace lamina::micro
