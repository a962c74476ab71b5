#include "micro/composite_voxel.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "micro/inside_query.hpp"
#include "micro/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

namespace lamina::micro {

namespace {

/// B(n): a -> sym(a (x) n) in lamina order with engineering shear; its
/// transpose maps a stress (lamina order) to the traction sigma n.
Eigen::Matrix<double, 6, 3> strainOfJump(const Eigen::Vector3d& n) {
  Eigen::Matrix<double, 6, 3> B = Eigen::Matrix<double, 6, 3>::Zero();
  B(0, 0) = n[0];
  B(1, 1) = n[1];
  B(2, 2) = n[2];
  B(3, 0) = n[1]; // gamma_xy = a_x n_y + a_y n_x
  B(3, 1) = n[0];
  B(4, 1) = n[2]; // gamma_yz
  B(4, 2) = n[1];
  B(5, 0) = n[2]; // gamma_xz
  B(5, 2) = n[0];
  return B;
}

/// Fraction of the layer @p inc (its periodic slabs) inside the voxel of
/// centre @p p and edges @p h: exact, the sum over the nearby slabs of the
/// box fractions between its two planes.
double layerFraction(const Inclusion& inc, const Eigen::Vector3d& p, const Eigen::Vector3d& h,
                     const Eigen::Vector3d& L) {
  const Eigen::Vector3d nu = inc.unitDirection(L);
  const double D = inc.periodicSpacing(L); // plane spacing
  const Eigen::Vector3d G = nu / D;
  double s = G.dot(nearestImage(p - inc.center, L));
  const double z0 = (s - std::round(s)) * D; // centre's distance from the nearest mid-plane
  const double w = 0.5 * nu.cwiseAbs().dot(h);
  const int K = static_cast<int>(std::ceil((w + 0.5 * inc.thickness) / D)) + 1;
  double f = 0;
  for (int k = -K; k <= K; ++k)
    f += boxFractionBelowPlane(h, nu, k * D + 0.5 * inc.thickness - z0) -
         boxFractionBelowPlane(h, nu, k * D - 0.5 * inc.thickness - z0);
  return std::clamp(f, 0.0, 1.0);
}

/// Inside samples of a line of kSubSamples (@p in(c), c = 0 .. kSubSamples-1),
/// all tested; [lo, hi) is set to the run from the first to the last inside.
template <class In>
int fullLine(const In& in, int& lo, int& hi) {
  int count = 0;
  lo = kSubSamples;
  hi = 0;
  for (int c = 0; c < kSubSamples; ++c)
    if (in(c)) {
      ++count;
      lo = std::min(lo, c);
      hi = c + 1;
    }
  if (count == 0)
    lo = hi = 0;
  return count;
}

/// The same count for a convex inclusion, whose inside samples along a line
/// are one run [lo, hi): starting from the previous line's run (@p lo, @p hi
/// on entry), a sample inside its middle confirms a run, and its ends are
/// moved sample by sample (neighbouring lines' ends differ by a sample or
/// two: about 5 tests per line instead of kSubSamples). Without a confirmed
/// run the line is tested in full.
template <class In>
int convexLine(const In& in, int& lo, int& hi) {
  if (lo >= hi)
    return fullLine(in, lo, hi);
  const int seed = (lo + hi - 1) / 2;
  if (!in(seed))
    return fullLine(in, lo, hi);
  // first inside: walk left from lo while inside, or right until inside
  int l = std::min(lo, seed);
  if (in(l))
    while (l > 0 && in(l - 1))
      --l;
  else
    while (!in(++l)) {
    }
  // one past the last inside
  int r = std::max(hi - 1, seed);
  if (in(r))
    while (r + 1 < kSubSamples && in(r + 1))
      ++r;
  else
    while (!in(--r)) {
    }
  lo = l;
  hi = r + 1;
  return hi - lo;
}

/// Inside samples c = 0 .. kSubSamples-1 of a line on which a sphere's,
/// ellipsoid's or axis fibre's quadratic form is q(c) = q0 + c (2 p + c s)
/// (InsideQuery::quadraticForm): q < 1 - kBoxMargin is inside, q > 1 +
/// kBoxMargin outside, in between @p exact(c) decides. The roots of q = 1
/// give the run of inside samples; its two end samples are checked inside
/// and their outer neighbours outside (q is convex: the rest follow).
/// Otherwise (a line grazing the surface between samples, or q constant)
/// every sample is tested.
template <class Exact>
int quadraticLine(double q0, double p, double s, const Exact& exact) {
  constexpr int last = kSubSamples - 1;
  auto q = [&](double c) { return q0 + c * (2 * p + c * s); };
  const double disc = p * p - s * (q0 - 1);
  if (s > 0 && disc >= 0) {
    const double root = std::sqrt(disc);
    // integer ceil / floor of the roots, clamped to the samples
    const double r1 = std::clamp((-p - root) / s, -1.0, double(kSubSamples));
    const double r2 = std::clamp((-p + root) / s, -1.0, double(kSubSamples));
    int lo = static_cast<int>(r1), hi = static_cast<int>(r2);
    lo += lo < r1;
    hi -= hi > r2;
    lo = std::max(lo, 0);
    hi = std::min(hi, last);
    if (lo <= hi && q(lo) < 1 - kBoxMargin && q(hi) < 1 - kBoxMargin &&
        (lo == 0 || q(lo - 1) > 1 + kBoxMargin) && (hi == last || q(hi + 1) > 1 + kBoxMargin))
      return hi - lo + 1;
  }
  if (s > 0 && q(std::clamp(-p / s, 0.0, double(last))) > 1 + kBoxMargin)
    return 0; // the smallest q on the line is outside
  int count = 0;
  for (int c = 0; c < kSubSamples; ++c) {
    const double qc = q(c);
    if (qc < 1 - kBoxMargin)
      ++count;
    else if (!(qc > 1 + kBoxMargin))
      count += exact(c);
  }
  return count;
}

/// Fraction of the curved inclusion @p inc in the voxel of lower corner
/// @p corner and edges @p h, counted on kSubSamples^3 points; -1 when its 8
/// corners lie on one side (not cut). An oblique fibre is tested only
/// against the copies of its axis that pass within r + |h|/2 of the voxel
/// centre, listed once per voxel (a copy holding a point of the voxel
/// passes that close): the same answer as contains(), without a search
/// over the periodic copies per sub-sample. Other shapes are tested by
/// @p query (the inclusion's prepared contains()).
double sampledFraction(const Inclusion& inc, const InsideQuery& query,
                       const Eigen::Vector3d& corner, const Eigen::Vector3d& h,
                       const Eigen::Vector3d& L) {
  const Eigen::Vector3d centre = corner + 0.5 * h;
  const bool oblique = inc.shape == Shape::Fiber && inc.axis < 0;
  const Eigen::Vector3d dir = inc.unitDirection(L);
  std::vector<Eigen::Vector3d> feet;
  if (oblique) {
    for (const Eigen::Vector3d& off : inc.axisOffsetsWithin(centre, inc.radius + 0.5 * h.norm(), L))
      feet.push_back(centre - off);
    if (feet.empty())
      return -1; // no copy comes near: the voxel is outside
  }
  // sphere, ellipsoid, axis-aligned fibre within one periodic image: the
  // quadratic form at x decides unless within kBoxMargin of the surface
  Eigen::Vector3d m0;
  const bool quadratic = query.quadraticForm(centre, 0.5 * h, m0);
  const Eigen::Matrix3d& M = query.form();
  auto inside = [&](const Eigen::Vector3d& x) {
    if (quadratic) {
      const double q = (m0 + M * (x - centre)).squaredNorm();
      if (q < 1 - kBoxMargin)
        return true;
      if (q > 1 + kBoxMargin)
        return false;
    }
    if (!oblique)
      return query.contains(x);
    for (const Eigen::Vector3d& foot : feet) {
      const Eigen::Vector3d v = x - foot;
      if ((v - v.dot(dir) * dir).squaredNorm() <= inc.radius * inc.radius)
        return true;
    }
    return false;
  };
  int in = 0;
  for (int c = 0; c < 8; ++c)
    in += inside(corner +
                 Eigen::Vector3d((c & 1) * h[0], ((c >> 1) & 1) * h[1], ((c >> 2) & 1) * h[2]));
  if (in == 0 || in == 8)
    return -1;
  auto point = [&](int a, int b, int c) -> Eigen::Vector3d {
    return corner + Eigen::Vector3d((a + 0.5) / kSubSamples * h[0], (b + 0.5) / kSubSamples * h[1],
                                    (c + 0.5) / kSubSamples * h[2]);
  };
  int count = 0;
  if (quadratic) {
    // the form along each line of samples, |base + c step|^2 (round-off a
    // few ulps, far below kBoxMargin)
    const Eigen::Vector3d step = M.col(2) * (h[2] / kSubSamples);
    const double s = step.squaredNorm();
    for (int a = 0; a < kSubSamples; ++a)
      for (int b = 0; b < kSubSamples; ++b) {
        const Eigen::Vector3d base = m0 + M * (point(a, b, 0) - centre);
        count += quadraticLine(base.squaredNorm(), base.dot(step), s,
                               [&](int c) { return query.contains(point(a, b, c)); });
      }
    return static_cast<double>(count) / (kSubSamples * kSubSamples * kSubSamples);
  }
  const bool convex = inc.shape == Shape::Sphere || inc.shape == Shape::Ellipsoid;
  int lo = 0, hi = 0; // the previous line's run of inside samples [lo, hi)
  for (int a = 0; a < kSubSamples; ++a)
    for (int b = 0; b < kSubSamples; ++b) {
      auto sample = [&](int c) { return inside(point(a, b, c)); };
      count += convex ? convexLine(sample, lo, hi) : fullLine(sample, lo, hi);
    }
  return static_cast<double>(count) / (kSubSamples * kSubSamples * kSubSamples);
}

} // namespace

double boxFractionBelowPlane(const Eigen::Vector3d& h, const Eigen::Vector3d& nu, double a) {
  // box [0, h]: nu.y <= a + nu.h/2; a negative component flips its axis
  double alpha = a + 0.5 * nu.dot(h);
  double m[3], l[3];
  int d = 0;
  const double scale = nu.cwiseAbs().dot(h);
  for (int i = 0; i < 3; ++i) {
    if (nu[i] < 0)
      alpha -= nu[i] * h[i];
    if (std::abs(nu[i]) * h[i] <= 1e-9 * scale)
      continue; // the plane is parallel to this axis: it does not enter
    m[d] = std::abs(nu[i]);
    l[d] = h[i];
    ++d;
  }
  double reach = 0; // alpha at which the plane has swept the whole box
  for (int i = 0; i < d; ++i)
    reach += m[i] * l[i];
  if (alpha <= 0)
    return 0.0;
  if (alpha >= reach)
    return 1.0;
  // inclusion-exclusion over the box corners:
  // V = sum_S (-1)^|S| (alpha - sum_{i in S} m_i l_i)_+^d / (d! prod m_i)
  double sum = 0, prod = 1, fact = 1;
  for (int i = 0; i < d; ++i) {
    prod *= m[i] * l[i];
    fact *= i + 1;
  }
  for (int S = 0; S < (1 << d); ++S) {
    double r = alpha;
    int sign = 1;
    for (int i = 0; i < d; ++i)
      if (S & (1 << i)) {
        r -= m[i] * l[i];
        sign = -sign;
      }
    if (r > 0)
      sum += sign * std::pow(r, d);
  }
  return std::clamp(sum / (fact * prod), 0.0, 1.0);
}

materials::Stiffness laminateStiffness(const materials::Stiffness& C1,
                                       const materials::Stiffness& C2, double c1,
                                       const Eigen::Vector3d& n) {
  const double c2 = 1 - c1;
  const Eigen::Matrix<double, 6, 3> B = strainOfJump(n.normalized());
  const materials::Matrix6 dC = C1.matrix() - C2.matrix();
  const Eigen::Matrix3d K =
      c2 * B.transpose() * C1.matrix() * B + c1 * B.transpose() * C2.matrix() * B;
  const Eigen::Matrix<double, 3, 6> BtdC = B.transpose() * dC;
  materials::Matrix6 C =
      c1 * C1.matrix() + c2 * C2.matrix() - c1 * c2 * BtdC.transpose() * K.ldlt().solve(BtdC);
  return materials::Stiffness(0.5 * (C + C.transpose()));
}

namespace {

/// A voxel an inclusion cuts: the voxel, the inclusion, the fraction inside.
struct Cut {
  std::size_t index;
  int which;
  double f;
};

/// @return (voxel, fraction inside) of every voxel of the grid @p n (edges
/// @p h, cell @p size) that @p inc cuts, in no fixed order
std::vector<std::pair<std::size_t, double>> voxelsCutBy(const Inclusion& inc,
                                                        const std::array<int, 3>& n,
                                                        const Eigen::Vector3d& size,
                                                        const Eigen::Vector3d& h) {
  const InsideQuery query(inc, size);
  std::array<int, 3> lo{}, hi{};
  voxelRange(inc, n, size, lo, hi);
  std::vector<std::pair<std::size_t, double>> found;
  core::ParallelErrors errors; // allocation, a query refusing a shape
#pragma omp parallel
  {
    std::vector<std::pair<std::size_t, double>> mine;
#pragma omp for schedule(dynamic)
    for (int i = lo[0]; i <= hi[0]; ++i)
      errors.run([&] {
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int k0 = lo[2]; k0 <= hi[2]; k0 += kVoxelRun) {
            // a run of voxels wholly on one side: no voxel of it is cut
            const int k1 = std::min(k0 + kVoxelRun - 1, hi[2]);
            if (inc.shape != Shape::Layer && query.runSide(i, j, k0, k1, h) != 0)
              continue;
            for (int k = k0; k <= k1; ++k) {
              const Eigen::Vector3d corner(i * h[0], j * h[1], k * h[2]);
              double f = 0;
              if (inc.shape == Shape::Layer) {
                f = layerFraction(inc, corner + 0.5 * h, h, size);
                const bool centre = query.contains(corner + 0.5 * h);
                if ((f == 0 && !centre) || (f == 1 && centre))
                  continue; // whole voxel on the side its centre sampled
              } else {
                // voxels wholly on one side (all 8 corners agree) need no corner tests
                if (query.boxSide(corner + 0.5 * h, 0.5 * h) != 0)
                  continue;
                f = sampledFraction(inc, query, corner, h, size);
                if (f < 0)
                  continue;
              }
              const std::size_t idx = wrappedVoxelIndex(i, j, k, n);
              mine.emplace_back(idx, f);
            }
          }
      });
#pragma omp critical
    errors.run([&] { found.insert(found.end(), mine.begin(), mine.end()); });
  }
  errors.rethrow();
  return found;
}

/// @return the composite voxel of the @p count cuts @p list of voxel
/// @p idx (sorted by inclusion), or nothing: several phases cut it (it
/// keeps the centre's phase), or every sub-sample agrees (then @p phase of
/// the voxel is set to the side they agree on)
std::optional<CompositeVoxel> compositeOf(const Cut* list, std::size_t count, std::size_t idx,
                                          const std::vector<Inclusion>& inclusions,
                                          const std::array<int, 3>& n, const Eigen::Vector3d& size,
                                          const Eigen::Vector3d& h,
                                          std::vector<std::int32_t>& phase) {
  // Inclusions never overlap, so the fractions of several inclusions of
  // one phase in a voxel add up (two crossing yarns, neighbouring
  // spheres); the normal is that of the interface nearest to halving the
  // voxel (a yarn-matrix-yarn sandwich has one normal up to its sign, to
  // which the laminate is blind). Inclusions of different phases: three
  // phases in one voxel, keep the centre's phase.
  std::size_t lead = 0;
  double f = 0;
  bool onePhase = true;
  for (std::size_t q = 0; q < count; ++q) {
    const double fq = list[q].f;
    onePhase = onePhase && inclusions[static_cast<std::size_t>(list[q].which)].phase ==
                               inclusions[static_cast<std::size_t>(list[0].which)].phase;
    f += fq;
    if (std::min(fq, 1 - fq) > std::min(list[lead].f, 1 - list[lead].f))
      lead = q;
  }
  if (!onePhase)
    return std::nullopt;
  f = std::min(f, 1.0);
  const Inclusion& inc = inclusions[static_cast<std::size_t>(list[lead].which)];
  if (f == 0 || f == 1) { // corners differ but every sub-sample agrees
    phase[idx] = f == 1 ? inc.phase : 0;
    return std::nullopt;
  }
  const Eigen::Vector3d centre = voxelCentre(idx, n, h);
  return CompositeVoxel{idx, inc.phase, 0, f, inc.normalAt(centre, size), list[lead].which};
}

} // namespace

std::vector<CompositeVoxel> findCompositeVoxels(const std::vector<Inclusion>& inclusions,
                                                const std::array<int, 3>& n,
                                                const Eigen::Vector3d& size,
                                                std::vector<std::int32_t>& phase) {
  const Eigen::Vector3d h(size[0] / n[0], size[1] / n[1], size[2] / n[2]);
  // (voxel, inclusion, fraction) of every inclusion that cuts a voxel
  std::vector<Cut> cut;
  for (std::size_t q = 0; q < inclusions.size(); ++q)
    for (const auto& [idx, f] : voxelsCutBy(inclusions[q], n, size, h))
      cut.push_back({idx, static_cast<int>(q), f});
  // by voxel, each voxel's inclusions in their order
  std::sort(cut.begin(), cut.end(), [](const Cut& a, const Cut& b) {
    return a.index != b.index ? a.index < b.index : a.which < b.which;
  });
  std::vector<CompositeVoxel> out;
  for (std::size_t first = 0, last = 0; first < cut.size(); first = last) {
    const std::size_t idx = cut[first].index;
    while (last < cut.size() && cut[last].index == idx)
      ++last;
    if (auto v = compositeOf(&cut[first], last - first, idx, inclusions, n, size, h, phase))
      out.push_back(*v);
  }
  return out; // in voxel order
}

VoxelMaterials voxelMaterials(const UnitCell& cell, const std::vector<materials::Stiffness>& C,
                              const std::vector<double>& density) {
  VoxelMaterials m{cell.phase.toVector(), C, density};
  // the stiffness of phase @p ph in voxel @p idx: rotated along its yarn's
  // path when the voxel is oriented (yarn_orientation.hpp), else the phase's
  auto stiffnessIn = [&](std::size_t idx, int ph) {
    const OrientedVoxel* o = findVoxel(cell.oriented, idx);
    const auto& Cp = C[static_cast<std::size_t>(ph)];
    if (!o || o->phase != ph)
      return Cp;
    return Cp.rotated(materials::axisRotation(o->axis, o->angle));
  };
  // whole oriented voxels share an entry per rotation: the foot, hence the
  // angle, depends only on the voxel's coordinates along the yarn and its
  // crimp axis, so a row of voxels across the yarn's width has one angle,
  // bit for bit (exact sharing, no quantisation)
  using Key = std::tuple<int, int, double>; // phase, axis, angle
  std::vector<std::pair<Key, std::size_t>> whole;
  for (const OrientedVoxel& o : cell.oriented)
    if (!findVoxel(cell.composites, o.index))
      whole.push_back({Key{o.phase, o.axis, o.angle}, o.index});
  std::sort(whole.begin(), whole.end());
  std::vector<Key> rotations;
  for (const auto& w : whole)
    if (rotations.empty() || rotations.back() != w.first)
      rotations.push_back(w.first);
  // entry base + i for composite voxel i, then base + composites + r for
  // rotation r (each entry its own slot: threads write disjoint entries)
  const std::size_t base = m.C.size(), nc = cell.composites.size();
  m.C.resize(base + nc + rotations.size());
  m.density.resize(base + nc + rotations.size());
  core::ParallelErrors errors; // a laminate refusing its plies
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nc); ++i)
    errors.run([&] {
      const CompositeVoxel& v = cell.composites[static_cast<std::size_t>(i)];
      const auto in = static_cast<std::size_t>(v.inside), out = static_cast<std::size_t>(v.outside);
      const std::size_t e = base + static_cast<std::size_t>(i);
      m.phase[v.index] = static_cast<std::int32_t>(e);
      m.C[e] = laminateStiffness(stiffnessIn(v.index, v.inside), C[out], v.fraction, v.normal);
      m.density[e] = v.fraction * density[in] + (1 - v.fraction) * density[out];
    });
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(rotations.size()); ++r)
    errors.run([&] {
      const auto& [ph, axis, angle] = rotations[static_cast<std::size_t>(r)];
      const std::size_t e = base + nc + static_cast<std::size_t>(r);
      m.C[e] = C[static_cast<std::size_t>(ph)].rotated(materials::axisRotation(axis, angle));
      m.density[e] = density[static_cast<std::size_t>(ph)];
    });
  errors.rethrow();
  for (std::size_t w = 0, r = 0; w < whole.size(); ++w) {
    if (whole[w].first != rotations[r])
      ++r;
    m.phase[whole[w].second] = static_cast<std::int32_t>(base + nc + r);
  }
  return m;
}

} // namespace lamina::micro
