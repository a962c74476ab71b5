// The k-means partitions of a reduced-order cell (homogenize/partition.hpp):
// deterministic (same labels twice, with one and with two threads), every
// partition non-empty and inside one phase, a Lloyd fixed point (each voxel
// nearest its own partition's mean), and on features of exactly two values
// per phase exactly the two sets of voxels that carry them.

#include "homogenize/field_operator.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/partition.hpp"
#include "reduced_order_cells.hpp"
#include "../materials/laminate_reduced_order.hpp"

#include <gtest/gtest.h>
#include <omp.h>

namespace lamina::test {
namespace {

using homogenize::Partitions;
using homogenize::PartitionMethod;
using homogenize::PartitionOptions;

constexpr std::size_t kF = homogenize::kConcentrationFeatures;

/// The strain concentration tensors of every voxel (column k: the voxel's
/// strain under unit macro strain k) from the six load cases.
std::vector<double> concentrationFeatures(const homogenize::Grid& grid,
                                          const std::vector<std::int32_t>& map,
                                          const std::vector<materials::Stiffness>& L) {
  homogenize::Options o;
  o.tol = 1e-10;
  o.threads = 1;
  o.estimate = homogenize::Estimate::Stress;
  o.precision = homogenize::Precision::Double;
  homogenize::Homogenizer h(grid, map, L, std::vector<double>(L.size(), 1000.0), o);
  const homogenize::FieldOperator D(grid);
  const std::size_t N = grid.size();
  std::vector<double> eps(6 * N), f(kF * N);
  h.setDisplacementSink([&](int k, const double* u) {
    std::array<double, 6> E{0, 0, 0, 0, 0, 0};
    E[static_cast<std::size_t>(k)] = 1;
    D.strain(u, E, eps.data());
    for (std::size_t v = 0; v < N; ++v)
      for (std::size_t i = 0; i < 6; ++i)
        f[kF * v + 6 * static_cast<std::size_t>(k) + i] = eps[i * N + v];
  });
  h.run();
  return f;
}

Partitions partitionWithThreads(int threads, const std::vector<std::int32_t>& map,
                                const std::vector<std::string>& names,
                                const std::vector<double>& f, const PartitionOptions& opt) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Partitions p = homogenize::makePartitions(map, names, f.data(), opt);
  omp_set_num_threads(saved);
  return p;
}

TEST(KMeansPartitions, DeterministicNonEmptyInsideOnePhaseAndAFixedPoint) {
  const std::array<int, 3> n{10, 10, 10};
  const std::vector<std::int32_t> map = inclusionsMap(n);
  const std::vector<double> f =
      concentrationFeatures(cubeGrid(n, 1e-3), map,
                            {materials::Stiffness::isotropic(3e9, 0.4),
                             materials::Stiffness::isotropic(70e9, 0.25)});
  const std::vector<std::string> names{"matrix", "stiff"};
  PartitionOptions opt;
  opt.method = PartitionMethod::KMeans;
  opt.per_phase = 4;
  const Partitions a = partitionWithThreads(1, map, names, f, opt);
  const Partitions b = partitionWithThreads(1, map, names, f, opt);
  const Partitions c = partitionWithThreads(2, map, names, f, opt);
  EXPECT_EQ(a.label, b.label);
  EXPECT_EQ(a.label, c.label);
  ASSERT_EQ(a.count(), 8);
  // phase-major numbering, K per phase, every partition non-empty and inside one phase
  EXPECT_EQ(a.phase, (std::vector<std::int32_t>{0, 0, 0, 0, 1, 1, 1, 1}));
  std::vector<std::size_t> count(8, 0);
  for (std::size_t v = 0; v < map.size(); ++v) {
    ASSERT_GE(a.label[v], 0);
    ++count[static_cast<std::size_t>(a.label[v])];
    EXPECT_EQ(a.phase[static_cast<std::size_t>(a.label[v])], map[v]) << v;
  }
  for (std::size_t p = 0; p < 8; ++p) {
    EXPECT_GT(count[p], 0u) << p;
    EXPECT_EQ(count[p], a.voxels[p]) << p;
  }
  // a Lloyd fixed point: each voxel is at least as near its own partition's
  // mean as any other partition's mean of its phase (the means formed here;
  // 1e-12 relative: the rounding of the means, summed in another order)
  std::vector<double> mean(8 * kF, 0.0);
  for (std::size_t v = 0; v < map.size(); ++v)
    for (std::size_t q = 0; q < kF; ++q)
      mean[static_cast<std::size_t>(a.label[v]) * kF + q] +=
          f[kF * v + q] / static_cast<double>(count[static_cast<std::size_t>(a.label[v])]);
  auto d2 = [&](std::size_t v, std::size_t p) {
    double s = 0;
    for (std::size_t q = 0; q < kF; ++q)
      s += std::pow(f[kF * v + q] - mean[p * kF + q], 2);
    return s;
  };
  for (std::size_t v = 0; v < map.size(); ++v) {
    const std::size_t own = static_cast<std::size_t>(a.label[v]);
    for (std::size_t p = 0; p < 8; ++p) {
      if (a.phase[p] == map[v]) {
        EXPECT_LE(d2(v, own), d2(v, p) * (1 + 1e-12) + 1e-30) << v << " " << p;
      }
    }
  }
  // another seed is another valid clustering, labelled by the same rules
  opt.seed = 7;
  const Partitions d = partitionWithThreads(1, map, names, f, opt);
  EXPECT_EQ(d.count(), 8);
}

// Four z-normal layers of four stiffnesses; layers 0 and 2 are called
// phase 0, layers 1 and 3 phase 1. Every voxel's feature is its layer's
// exact strain concentration (tests/materials/laminate_reduced_order.hpp):
// two distinct values per phase, so K = 2 must find exactly the layers.
TEST(KMeansPartitions, TwoValuedFeaturesGiveExactlyTheTwoSets) {
  const std::vector<materials::Matrix6> L{materials::Stiffness::isotropic(3e9, 0.4).matrix(),
                                          materials::Stiffness::isotropic(70e9, 0.25).matrix(),
                                          materials::Stiffness::isotropic(10e9, 0.3).matrix(),
                                          materials::Stiffness::isotropic(200e9, 0.3).matrix()};
  const std::vector<double> c{0.25, 0.25, 0.25, 0.25};
  std::vector<materials::Matrix6> A, P;
  laminateReducedOrder(L, c, A, P);
  const std::array<int, 3> n{2, 3, 8};
  const std::vector<std::int32_t> layer_of{0, 0, 1, 1, 2, 2, 3, 3};
  const std::vector<std::int32_t> layer = laminateMap(n, layer_of);
  std::vector<std::int32_t> map;
  std::vector<double> f;
  for (std::int32_t l : layer) {
    map.push_back(l % 2);
    const materials::Matrix6& a = A[static_cast<std::size_t>(l)];
    for (int k = 0; k < 6; ++k)
      for (int i = 0; i < 6; ++i)
        f.push_back(a(i, k));
  }
  PartitionOptions opt;
  opt.method = PartitionMethod::KMeans;
  opt.per_phase = 2;
  const Partitions p = homogenize::makePartitions(map, {"even", "odd"}, f.data(), opt);
  ASSERT_EQ(p.count(), 4);
  // numbered phase-major, then by lowest voxel: layer 0, 2 (phase 0), 1, 3
  const std::int32_t partition_of_layer[4] = {0, 2, 1, 3};
  for (std::size_t v = 0; v < layer.size(); ++v)
    EXPECT_EQ(p.label[v], partition_of_layer[layer[v]]) << v;
}

// A phase whose voxels all carry one feature still gets K non-empty
// partitions (an empty cluster is re-seeded), and K = 1 is the phase.
TEST(KMeansPartitions, IdenticalFeaturesStillGiveNonEmptyPartitions) {
  const std::vector<std::int32_t> map{0, 0, 0, 1, 1, 0, 1};
  const std::vector<double> f(kF * map.size(), 0.5);
  PartitionOptions opt;
  opt.method = PartitionMethod::KMeans;
  opt.per_phase = 3;
  const Partitions p = homogenize::makePartitions(map, {"a", "b"}, f.data(), opt);
  ASSERT_EQ(p.count(), 6);
  for (std::size_t q = 0; q < 6; ++q)
    EXPECT_GT(p.voxels[q], 0u) << q;
  opt.per_phase = 1;
  const Partitions one = homogenize::makePartitions(map, {"a", "b"}, f.data(), opt);
  const Partitions phase = homogenize::makePartitions(map, {"a", "b"}, nullptr, PartitionOptions{});
  EXPECT_EQ(one.label, map);
  EXPECT_EQ(phase.label, map);
}

// A phase without voxels gets no partition; the numbering skips it.
TEST(KMeansPartitions, PhaseWithoutVoxelsGetsNoPartition) {
  const std::vector<std::int32_t> map{0, 2, 2, 0};
  const Partitions p = homogenize::makePartitions(map, {"a", "unused", "c"}, nullptr, {});
  EXPECT_EQ(p.phase, (std::vector<std::int32_t>{0, 2}));
  EXPECT_EQ(p.label, (std::vector<std::int32_t>{0, 1, 1, 0}));
}

} // namespace
} // namespace lamina::test
