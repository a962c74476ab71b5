#pragma once
/// @file cluster_interaction.hpp
/// @brief The interaction tensors of clustering analysis (Liu, Bessa and
/// Liu 2016, "Self-consistent clustering analysis: an efficient multi-scale
/// scheme for inelastic heterogeneous materials", section 2: the
/// Lippmann-Schwinger equation averaged over clusters) on a voxel cell's
/// partitions, with the periodic Green
/// operator of the rotated scheme the full-field solver discretizes with
/// (green_operator.hpp).
///
/// In a homogeneous isotropic reference medium (Lame lambda0, mu0) the
/// strain of a periodic polarization tau (a stress) is eps = -Gamma0 tau,
/// and the rotated scheme's Gamma0 has, per Fourier mode, the real symbol
/// of the continuum operator with the wave vector replaced by the real
/// vector q of green_operator.hpp (n = q / |q|; modes with q = 0 map to
/// zero):
///
///     Gamma0_ijkl = (Ga_ijkl - beta Gb_ijkl) / mu0,  beta = (lambda0 + mu0) / (lambda0 + 2 mu0),
///     Ga_ijkl = (d_ik n_j n_l + d_il n_j n_k + d_jk n_i n_l + d_jl n_i n_k) / 4,
///     Gb_ijkl = n_i n_j n_k n_l.
///
/// The partition means of that strain, for a polarization uniform on each
/// partition, are eps^(I) = -sum_J G^(IJ) tau^(J) with
///
///     G^(IJ) = (Ga^(IJ) - beta Gb^(IJ)) / mu0,
///     Ga^(IJ) = 1 / (N_I N) sum_xi Re(conj(chi_I(xi)) chi_J(xi)) Ga(xi)   (and Gb alike),
///
/// chi_I the unnormalized transform of partition I's indicator, N_I its
/// voxels, N the cell's. So the two fixed arrays Ga, Gb give G for any
/// reference medium: that is what lets the law move its reference medium
/// at every step. Every matrix is 6x6 in lamina order, rows engineering
/// strain, columns stress (a shear row and a shear column each carry a
/// factor 2 of the tensor entry). Exact identities: sum_I c_I G^(IJ) = 0 (a
/// periodic strain has zero mean) and c_I G^(IJ) = (c_J G^(JI))^T.
///
/// Cost: one real transform per partition, then per Fourier mode the 6x6
/// symbols and every pair of partitions: about 75 n^2 N / 2 flops (n
/// partitions). Memory: the n half spectra, 8 n N bytes, and 8 partial sums
/// over fixed blocks of modes, 4.6 n^2 kB; the blocks are added in order, so
/// the result does not depend on the number of threads.

#include "homogenize/grid.hpp"
#include "materials/stiffness.hpp"

#include <cstdint>
#include <vector>

namespace lamina::homogenize {

/// The two fixed parts of the interaction tensors (see the file comment).
struct ClusterInteraction {
  std::vector<materials::Matrix6> Ga; ///< n * n: Ga[I * n + J] = Ga^(IJ)
  std::vector<materials::Matrix6> Gb; ///< n * n: Gb[I * n + J] = Gb^(IJ)
};

/// Computes Ga and Gb of the partitions @p label (one per voxel of @p
/// grid, in [0, n)), each with @p voxels[I] > 0 voxels.
/// @param threads OpenMP threads for the sum over modes (0: the default)
ClusterInteraction clusterInteraction(const Grid& grid, const std::vector<std::int32_t>& label,
                                      const std::vector<std::size_t>& voxels, int threads = 0);

} // namespace lamina::homogenize
