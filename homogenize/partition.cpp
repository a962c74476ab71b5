#include "homogenize/partition.hpp"

#include "core/error.hpp"

#include <omp.h>

#include <algorithm>
#include <limits>
#include <random>

namespace lamina::homogenize {

namespace {

constexpr std::size_t kF = static_cast<std::size_t>(kConcentrationFeatures);

/// A uniform number in [0, 1) from the engine's top 53 bits (the same on
/// every standard library, unlike std::uniform_real_distribution).
double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double distance2(const double* a, const double* b) {
  double d = 0;
  for (std::size_t f = 0; f < kF; ++f) {
    const double t = a[f] - b[f];
    d += t * t;
  }
  return d;
}

/// k-means of the points of one phase (their voxel indices in increasing
/// order) into K clusters; the method of partition.hpp.
class KMeans {
public:
  KMeans(const std::vector<std::size_t>& points, const double* features, int K)
      : points_(points), features_(features), K_(static_cast<std::size_t>(K)),
        centre_(K_ * kF, 0.0), label_(points.size(), -1), d2_(points.size(), 0.0) {}

  /// Seeds, iterates; @return the Lloyd iterations done
  int run(std::mt19937_64& rng, int max_iterations) {
    seed(rng);
    int it = 0;
    while (it < max_iterations) {
      ++it;
      const bool changed = assign();
      const bool reseeded = fillEmpty();
      updateCentres();
      if (!changed && !reseeded)
        break;
    }
    return it;
  }

  /// @return the cluster of each point, numbered by lowest voxel index
  std::vector<std::int32_t> labels() const {
    std::vector<std::int32_t> renumber(K_, -1), out(points_.size());
    std::int32_t next = 0;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      std::int32_t& r = renumber[static_cast<std::size_t>(label_[i])];
      if (r < 0)
        r = next++;
      out[i] = r;
    }
    return out;
  }

private:
  const double* feature(std::size_t i) const { return features_ + kF * points_[i]; }

  /// k-means++: centre 0 uniform, each next one drawn with probability
  /// d^2 / sum d^2 (the sum in point order); all d^2 zero: uniform.
  void seed(std::mt19937_64& rng) {
    const std::size_t n = points_.size();
    auto pick = [&](std::size_t i, std::size_t c) {
      std::copy(feature(i), feature(i) + kF, &centre_[c * kF]);
    };
    pick(std::min(n - 1, static_cast<std::size_t>(uniform(rng) * static_cast<double>(n))), 0);
    std::fill(d2_.begin(), d2_.end(), std::numeric_limits<double>::max());
    for (std::size_t c = 1; c < K_; ++c) {
      nearestTo(c - 1);
      double total = 0;
      for (double d : d2_)
        total += d;
      const double u = uniform(rng);
      std::size_t chosen = std::min(n - 1, static_cast<std::size_t>(u * static_cast<double>(n)));
      if (total > 0) { // the first point whose running sum passes u * total
        const double target = u * total;
        double sum = 0;
        for (std::size_t i = 0; i < n; ++i) {
          if (!(d2_[i] > 0))
            continue;
          sum += d2_[i];
          chosen = i; // the last point with d^2 > 0 if rounding keeps sum <= target
          if (sum > target)
            break;
        }
      }
      pick(chosen, c);
    }
  }

  /// d2 = min(d2, distance^2 to centre c), on the threads
  void nearestTo(std::size_t c) {
    const long n = static_cast<long>(points_.size());
    const double* ctr = &centre_[c * kF];
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) {
      const std::size_t ui = static_cast<std::size_t>(i);
      d2_[ui] = std::min(d2_[ui], distance2(feature(ui), ctr));
    }
  }

  /// Each point to its nearest centre (a tie keeps its cluster, else the
  /// lowest); d2 = its distance^2. @return whether a label changed
  bool assign() {
    const long n = static_cast<long>(points_.size());
    long changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed)
    for (long i = 0; i < n; ++i) {
      const std::size_t ui = static_cast<std::size_t>(i);
      const double* f = feature(ui);
      std::int32_t best = -1;
      double best_d = std::numeric_limits<double>::max();
      for (std::size_t c = 0; c < K_; ++c) {
        const double d = distance2(f, &centre_[c * kF]);
        if (d < best_d) {
          best_d = d;
          best = static_cast<std::int32_t>(c);
        }
      }
      const std::int32_t now = label_[ui];
      if (now >= 0 && distance2(f, &centre_[static_cast<std::size_t>(now) * kF]) <= best_d)
        best = now; // a tie keeps the current cluster
      changed += best != now;
      label_[ui] = best;
      d2_[ui] = distance2(f, &centre_[static_cast<std::size_t>(best) * kF]);
    }
    return changed > 0;
  }

  /// @return the number of points of each cluster
  std::vector<std::size_t> counts() const {
    std::vector<std::size_t> count(K_, 0);
    for (std::int32_t l : label_)
      ++count[static_cast<std::size_t>(l)];
    return count;
  }
  /// Re-seeds every empty cluster with the point farthest from its own
  /// centre among clusters of two or more points. @return whether any was
  bool fillEmpty() {
    std::vector<std::size_t> count = counts();
    bool any = false;
    for (std::size_t c = 0; c < K_; ++c) {
      if (count[c] > 0)
        continue;
      std::size_t far = points_.size();
      for (std::size_t i = 0; i < points_.size(); ++i)
        if (count[static_cast<std::size_t>(label_[i])] > 1 &&
            (far == points_.size() || d2_[i] > d2_[far]))
          far = i;
      LAMINA_CHECK(far < points_.size(), "k-means: no voxel to re-seed an empty cluster");
      --count[static_cast<std::size_t>(label_[far])];
      label_[far] = static_cast<std::int32_t>(c);
      count[c] = 1;
      d2_[far] = 0;
      std::copy(feature(far), feature(far) + kF, &centre_[c * kF]);
      any = true;
    }
    return any;
  }

  /// Each centre the mean of its points (sums in point order)
  void updateCentres() {
    std::fill(centre_.begin(), centre_.end(), 0.0);
    const std::vector<std::size_t> count = counts();
    for (std::size_t i = 0; i < points_.size(); ++i) {
      double* c = &centre_[static_cast<std::size_t>(label_[i]) * kF];
      const double* f = feature(i);
      for (std::size_t a = 0; a < kF; ++a)
        c[a] += f[a];
    }
    for (std::size_t c = 0; c < K_; ++c)
      for (std::size_t a = 0; a < kF; ++a)
        centre_[c * kF + a] /= static_cast<double>(count[c]);
  }

  const std::vector<std::size_t>& points_;
  const double* features_;
  std::size_t K_;
  std::vector<double> centre_;      // K x 36
  std::vector<std::int32_t> label_; // per point
  std::vector<double> d2_;          // per point: distance^2 to its (nearest) centre
};

} // namespace

std::vector<std::size_t> voxelsPerPhase(const std::vector<std::int32_t>& phase,
                                        std::size_t phases) {
  std::vector<std::size_t> count(phases, 0);
  for (std::int32_t p : phase) {
    LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < phases, "phase index ", p,
                 " is not one of the ", phases, " phases");
    ++count[static_cast<std::size_t>(p)];
  }
  return count;
}

void checkPartitionOptions(const std::vector<std::int32_t>& phase,
                           const std::vector<std::string>& names, const PartitionOptions& opt) {
  const ErrorContext where{"", 0, opt.option};
  if (opt.method == PartitionMethod::Phase)
    return;
  if (opt.per_phase < 1)
    throw Error("the number of partitions per phase must be at least 1 (got " +
                    std::to_string(opt.per_phase) + ")",
                where);
  if (opt.max_iterations < 1)
    throw Error("k-means needs at least one Lloyd iteration", where);
  const std::vector<std::size_t> count = voxelsPerPhase(phase, names.size());
  for (std::size_t p = 0; p < names.size(); ++p)
    if (count[p] > 0 && count[p] < static_cast<std::size_t>(opt.per_phase))
      throw Error(std::to_string(opt.per_phase) + " partitions per phase: phase '" + names[p] +
                      "' has only " + std::to_string(count[p]) + " voxels",
                  where);
}

Partitions makePartitions(const std::vector<std::int32_t>& phase,
                          const std::vector<std::string>& names, const double* features,
                          const PartitionOptions& opt) {
  checkPartitionOptions(phase, names, opt);
  const std::size_t phases = names.size();
  std::vector<std::vector<std::size_t>> points(phases);
  for (std::size_t v = 0; v < phase.size(); ++v)
    points[static_cast<std::size_t>(phase[v])].push_back(v);
  Partitions out;
  out.label.assign(phase.size(), -1);
  out.iterations.assign(phases, 0);
  const bool kmeans = opt.method == PartitionMethod::KMeans;
  LAMINA_CHECK(!kmeans || features, "k-means partitions need the strain concentration features");
  for (std::size_t p = 0; p < phases; ++p) {
    const std::vector<std::size_t>& pts = points[p];
    if (pts.empty())
      continue;
    const std::int32_t first = out.count();
    std::vector<std::int32_t> local(pts.size(), 0);
    int K = 1;
    if (kmeans) {
      K = opt.per_phase;
      std::mt19937_64 rng(opt.seed + 0x9E3779B97F4A7C15ULL * (p + 1)); // one stream per phase
      KMeans km(pts, features, K);
      out.iterations[p] = km.run(rng, opt.max_iterations);
      local = km.labels();
    }
    for (int c = 0; c < K; ++c) {
      out.phase.push_back(static_cast<std::int32_t>(p));
      out.voxels.push_back(0);
    }
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::int32_t l = first + local[i];
      out.label[pts[i]] = l;
      ++out.voxels[static_cast<std::size_t>(l)];
    }
  }
  for (std::size_t n : out.voxels)
    LAMINA_CHECK(n > 0, "a partition has no voxel");
  return out;
}

} // namespace lamina::homogenize
