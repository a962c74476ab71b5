#pragma once
/// @file partition.hpp
/// @brief The partitions of a reduced-order cell (polyurea chapter eq. 29):
/// disjoint sets of voxels, each inside one phase, on which the eigenstrain
/// is taken uniform.
///
/// Two methods (PartitionMethod):
/// - Phase (the default): one partition per phase that has voxels.
/// - KMeans: per phase, K clusters of its voxels by k-means on their
///   elastic strain concentration tensors, the clustering of
///   self-consistent clustering analysis (Z. Liu, M. A. Bessa, W. K. Liu,
///   "Self-consistent clustering analysis: an efficient multi-scale scheme
///   for inelastic heterogeneous materials", CMAME 306 (2016), section
///   2.2): the feature of a voxel is the 6x6 matrix whose column k is its
///   strain under unit macro strain k (36 numbers, lamina order,
///   engineering shear), and voxels that respond alike share a partition.
///   Seeding: k-means++ (Arthur and Vassilvitskii 2007): the first centre a
///   voxel drawn uniformly, each next one drawn with probability
///   proportional to its squared distance to the nearest centre so far,
///   from a std::mt19937_64 seeded with the seed (an option) and the phase
///   index; the uniform numbers are formed from the engine's 64-bit output
///   (top 53 bits), not by a library distribution, so the draws are the
///   same with every standard library. Then Lloyd iterations until the
///   labels no longer change (a fixed point) or max_iterations: each voxel
///   to its nearest centre (a tie keeps the voxel's current cluster, else
///   the lowest-numbered), a cluster left empty re-seeded with the voxel
///   farthest from its own centre among clusters of two or more voxels (the
///   lowest voxel index on a tie), each centre the mean of its voxels.
///
/// Determinism: the result depends only on the features, K and the seed.
/// The per-voxel work (distances, the nearest centre) runs on the OpenMP
/// threads; every sum (the seeding's total, the centres) runs serially in
/// voxel order, so the labels are the same with any thread count.
///
/// Numbering: phase-major (all partitions of phase 0 first, then phase 1,
/// ...); within a phase the clusters are numbered in the order of their
/// lowest voxel index. A phase without voxels gets no partition.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lamina::homogenize {

/// Features per voxel: the 6x6 strain concentration tensor, stored
/// column-major (feature 6 k + i is strain component i under unit macro
/// strain k).
inline constexpr int kConcentrationFeatures = 36;

/// Default seed of the k-means++ seeding.
inline constexpr std::uint64_t kDefaultPartitionSeed = 2016;

/// How a cell is split into partitions.
enum class PartitionMethod {
  Phase, ///< one partition per phase
  KMeans ///< K per phase, k-means on the strain concentration tensors
};

/// The choice of partitions.
struct PartitionOptions {
  PartitionMethod method = PartitionMethod::Phase; ///< how
  int per_phase = 1;                               ///< K (KMeans)
  std::uint64_t seed = kDefaultPartitionSeed;      ///< k-means++ seed (KMeans)
  int max_iterations = 300;                        ///< cap on the Lloyd iterations (KMeans)
  std::string option = "--partitions";             ///< names K in error messages
};

/// The partitions of a cell.
struct Partitions {
  std::vector<std::int32_t> label; ///< per voxel: its partition
  std::vector<std::int32_t> phase; ///< per partition: its phase
  std::vector<std::size_t> voxels; ///< per partition: its number of voxels (> 0)
  std::vector<int> iterations;     ///< per phase: Lloyd iterations (0: not clustered)
  /// @return the number of partitions
  int count() const { return static_cast<int>(phase.size()); }
};

/// @return the number of voxels of each of @p phases phases in @p phase;
/// throws lamina::Error for an index outside [0, phases)
std::vector<std::size_t> voxelsPerPhase(const std::vector<std::int32_t>& phase,
                                        std::size_t phases);

/// Checks @p opt against the phase map before anything is computed: K >= 1
/// and, with KMeans, no phase with voxels has fewer than K. Throws
/// lamina::Error naming opt.option and the phase (@p names: one per phase).
void checkPartitionOptions(const std::vector<std::int32_t>& phase,
                           const std::vector<std::string>& names, const PartitionOptions& opt);

/// Splits the voxels of @p phase (one index per voxel into @p names) as
/// @p opt says. @p features: kConcentrationFeatures doubles per voxel
/// (voxel-major), read by KMeans only (may be null for Phase). Runs
/// checkPartitionOptions first.
Partitions makePartitions(const std::vector<std::int32_t>& phase,
                          const std::vector<std::string>& names, const double* features,
                          const PartitionOptions& opt);

} // namespace lamina::homogenize
