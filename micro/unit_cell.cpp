#include "micro/unit_cell.hpp"

#include "core/error.hpp"
#include "core/resources.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/image_cell.hpp"
#include "micro/yarn_orientation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace lamina::micro {

namespace {

[[noreturn]] void groupError(const CellSpec& spec, const InclusionGroup& g,
                             const std::string& msg) {
  throw Error(msg, {spec.file, 0, g.key});
}

void checkFits(const CellSpec& spec, const InclusionGroup& g, const Inclusion& inc) {
  if ((inc.shape == Shape::Fiber || inc.shape == Shape::Layer) && inc.axis < 0) {
    const double width = inc.shape == Shape::Fiber ? 2 * inc.radius : inc.thickness;
    if (width + g.min_gap >= inc.periodicSpacing(spec.size))
      groupError(spec, g,
                 "the oblique " + toString(inc.shape) + " (with min_gap) is wider than the " +
                     "spacing of its periodic copies (" +
                     std::to_string(inc.periodicSpacing(spec.size)) +
                     "): lower its size or volume_fraction");
    return;
  }
  if (inc.shape == Shape::Yarn && !(0.5 * (inc.thickness + g.min_gap) < inc.minCurvatureRadius()))
    groupError(spec, g,
               "half the yarn's thickness (with min_gap) exceeds the smallest radius of "
               "curvature of its path (1 / (A k^2) = " +
                   std::to_string(inc.minCurvatureRadius()) +
                   "): the swept section would fold over itself; lower thickness or amplitude, "
                   "or raise wavelength");
  const Eigen::Vector3d e = inc.halfExtent(spec.size);
  for (int i = 0; i < 3; ++i) {
    const bool unbounded =
        ((inc.shape == Shape::Fiber || inc.shape == Shape::Yarn) && i == inc.axis) ||
        (inc.shape == Shape::Layer && i != inc.axis);
    if (!unbounded && 2 * e[i] + g.min_gap >= spec.size[i])
      groupError(spec, g,
                 "inclusion (with min_gap) does not fit in the cell along axis " +
                     std::string(1, "xyz"[i]) +
                     (inc.shape == Shape::Yarn && i == inc.crimp
                          ? " (a yarn spans 2 amplitude + thickness along its crimp axis)"
                          : "") +
                     ": lower its size or volume_fraction");
  }
}

/// @return how many copies of @p proto group @p g places: its lattice, its
/// count, or (random, by volume fraction) as many of the prototype's size as
/// reach the fraction of a cell of volume @p V
int copiesOf(const CellSpec& spec, const InclusionGroup& g, const Inclusion& proto, double V) {
  if (g.placement == Placement::Lattice)
    return g.lattice[0] * g.lattice[1] * g.lattice[2];
  if (g.placement != Placement::Random)
    return 1;
  if (g.count > 0)
    return g.count;
  // checked as a double before the cast (a tiny radius asks for billions)
  const double wanted = std::round(*g.volume_fraction * V / proto.volume(spec.size));
  if (!(wanted <= static_cast<double>(kMaxInclusions)))
    groupError(spec, g,
               "volume_fraction with this inclusion size needs " + std::to_string(wanted) +
                   " inclusions; at most " + std::to_string(kMaxInclusions) +
                   " per cell: give count or larger inclusions");
  return std::max(1, static_cast<int>(wanted));
}

/// @return whether @p c keeps @p gap from every inclusion of @p placed
bool clearOf(const Inclusion& c, const std::vector<Inclusion>& placed, double gap,
             const Eigen::Vector3d& size) {
  for (const Inclusion& o : placed)
    if (overlaps(c, o, gap, size))
      return false;
  return true;
}

/// Places the copies of @p proto on group @p g's lattice (cell-centred),
/// each clear of @p placed and of one another, after @p placed.
void placeLattice(const CellSpec& spec, const InclusionGroup& g, const Inclusion& proto,
                  std::vector<Inclusion>& placed) {
  std::vector<Inclusion> mine;
  for (int i = 0; i < g.lattice[0]; ++i)
    for (int j = 0; j < g.lattice[1]; ++j)
      for (int k = 0; k < g.lattice[2]; ++k) {
        Inclusion c = proto;
        c.center = Eigen::Vector3d((i + 0.5) / g.lattice[0], (j + 0.5) / g.lattice[1],
                                   (k + 0.5) / g.lattice[2])
                       .cwiseProduct(spec.size);
        if (!clearOf(c, placed, g.min_gap, spec.size))
          groupError(spec, g, "lattice inclusions overlap (with min_gap): lower the fraction");
        mine.push_back(c);
      }
  for (const auto& c : mine) {
    for (const auto& o : mine)
      if (&o != &c && overlaps(c, o, g.min_gap, spec.size))
        groupError(spec, g, "lattice inclusions overlap (with min_gap): lower the fraction");
  }
  placed.insert(placed.end(), mine.begin(), mine.end());
}

/// Places @p copies copies of @p proto by random sequential adsorption
/// with periodic wrap, reproducible from group @p g's seed, after @p placed;
/// @p tests counts the overlap tests of the whole cell (bounded).
void placeRandom(const CellSpec& spec, const InclusionGroup& g, const Inclusion& proto, int copies,
                 std::vector<Inclusion>& placed, std::int64_t& tests) {
  std::mt19937_64 rng(g.seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int c = 0; c < copies; ++c) {
    bool ok = false;
    for (int a = 0; a < g.max_attempts && !ok; ++a) {
      tests += std::max<std::int64_t>(1, static_cast<std::int64_t>(placed.size()));
      if (tests > spec.max_overlap_tests)
        groupError(spec, g,
                   "random placement stopped at inclusion " + std::to_string(c + 1) + " of " +
                       std::to_string(copies) + ", attempt " + std::to_string(a + 1) +
                       ": the cell's placement reached its bound of " +
                       std::to_string(spec.max_overlap_tests) +
                       " overlap tests (attempts x inclusions placed); lower count, "
                       "volume_fraction, min_gap or max_attempts, or use fewer, larger "
                       "inclusions");
      Inclusion cand = proto;
      for (int i = 0; i < 3; ++i)
        cand.center[i] = u01(rng) * spec.size[i];
      if (clearOf(cand, placed, g.min_gap, spec.size)) {
        placed.push_back(cand);
        ok = true;
      }
    }
    if (!ok)
      groupError(spec, g,
                 "random placement failed for inclusion " + std::to_string(c + 1) + " of " +
                     std::to_string(copies) + " after " + std::to_string(g.max_attempts) +
                     " attempts: lower volume_fraction or min_gap, or use fewer, larger "
                     "inclusions");
  }
}

} // namespace

std::vector<Inclusion> placeInclusions(const CellSpec& spec, std::vector<double>& target,
                                       std::vector<double>& analytic) {
  std::vector<Inclusion> placed;
  const double V = spec.size.prod();
  target.clear();
  analytic.clear();
  std::int64_t total = 0;
  std::int64_t tests = 0; // overlap tests of the random placement, bounded
  for (const InclusionGroup& g : spec.groups) {
    Inclusion proto = g.prototype;
    const int copies = copiesOf(spec, g, proto, V);
    total += copies;
    if (total > kMaxInclusions)
      groupError(spec, g,
                 "the cell's groups hold " + std::to_string(total) + " inclusions; at most " +
                     std::to_string(kMaxInclusions) + " per cell (placement tests every pair)");
    if (g.volume_fraction) {
      // scale all lengths so that `copies` inclusions reach the target exactly
      const double s = std::pow(*g.volume_fraction * V / (copies * proto.volume(spec.size)),
                                1.0 / proto.dimension());
      proto.scale(s);
    }
    target.push_back(g.volume_fraction ? *g.volume_fraction
                                       : std::numeric_limits<double>::quiet_NaN());
    analytic.push_back(copies * proto.volume(spec.size) / V);
    checkFits(spec, g, proto);
    if (g.placement == Placement::Single) {
      if (!clearOf(proto, placed, g.min_gap, spec.size))
        groupError(spec, g, "inclusion overlaps an earlier one");
      placed.push_back(proto);
    } else if (g.placement == Placement::Lattice) {
      placeLattice(spec, g, proto, placed);
    } else {
      placeRandom(spec, g, proto, copies, placed, tests);
    }
  }
  return placed;
}

UnitCell buildCell(const CellSpec& spec, std::array<int, 3> n) {
  if (n[0] == 0 && n[1] == 0 && n[2] == 0)
    n = spec.resolution;
  if (spec.image) {
    if (n != spec.resolution)
      throw Error("an image cell takes its resolution from the image (" +
                      std::to_string(spec.resolution[0]) + " x " +
                      std::to_string(spec.resolution[1]) + " x " +
                      std::to_string(spec.resolution[2]) +
                      "); use downsample = F or crop to change it",
                  {spec.file, 0, "resolution"});
    return buildImageCell(spec);
  }
  for (int d : n)
    if (d < 2 || d > kMaxResolution)
      throw Error("resolution must be in [2, " + std::to_string(kMaxResolution) +
                      "] voxels per direction, got " + std::to_string(d),
                  {spec.file, 0, "resolution"});
  // The phase map (4 B per voxel) and its copy on the way to HDF5.
  core::requireMemory(8.0 * double(n[0]) * double(n[1]) * double(n[2]),
                      "a phase map of " + std::to_string(n[0]) + " x " + std::to_string(n[1]) +
                          " x " + std::to_string(n[2]) + " voxels",
                      {spec.file, 0, "resolution"});
  UnitCell cell;
  cell.n = n;
  cell.size = spec.size;
  cell.phase_count = static_cast<int>(spec.phases.size());
  cell.inclusions = placeInclusions(spec, cell.target_fraction, cell.analytic_fraction);
  cell.phase = voxelize(cell.inclusions, n, spec.size);
  if (spec.composite_voxels.value_or(kCompositeVoxelsByDefault)) {
    cell.composites = findCompositeVoxels(cell.inclusions, n, spec.size, cell.phase.values());
    // a voxel cut by a pore stays whole (its centre's phase): the laminate
    // with a void ply is singular, and on the sphere cell it took 50-200
    // times the iterations and came out 25 % softer than the staircase at
    // 16^3 (docs/homogenize-solver.md, "Pores")
    auto pore = [&](int ph) { return spec.phases[static_cast<std::size_t>(ph)].isVoid(); };
    cell.composites.erase(
        std::remove_if(cell.composites.begin(), cell.composites.end(),
                       [&](const CompositeVoxel& v) { return pore(v.inside) || pore(v.outside); }),
        cell.composites.end());
  }
  std::vector<bool> anisotropic; // the phases a rotation changes
  for (const Phase& ph : spec.phases)
    anisotropic.push_back(!ph.isotropic());
  cell.oriented = orientYarnVoxels(cell.inclusions, anisotropic, n, spec.size, cell.phase.values(),
                                   cell.composites);
  cell.countFractions();
  return cell;
}

} // namespace lamina::micro
