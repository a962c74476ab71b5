#pragma once
/// @file laminate_reduced_order.hpp
/// @brief Test oracle: the exact reduced-order matrices (A^(alpha), P^(beta
/// alpha) of materials/reduced_order.hpp) of a periodic laminate whose layers
/// are normal to z, one partition per layer, by the classical laminate
/// argument, independent of any FFT solver.
///
/// In a laminate every field is uniform in each layer. Compatibility keeps
/// the in-plane strains (lamina components t = xx, yy, xy) of every layer
/// equal to the macro strain; equilibrium makes the out-of-plane tractions
/// (n = zz, yz, xz) one common vector s. With an eigenstrain mu^(a) in layer
/// a: sigma^(a) = L_a (eps^(a) - mu^(a)), so
///     eps^(a)_n = N_a (s - L_a,nt E_t + (L_a mu^(a))_n),   N_a = L_a,nn^-1,
/// and sum_a c_a eps^(a)_n = E_n fixes s. Both maps are linear: A's column k
/// is the layer strain for E = e_k, mu = 0; P^(b a)'s column J is layer b's
/// strain for E = 0 and mu^(a) = e_J.
#include "materials/stiffness.hpp"

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace lamina::test {

/// Lamina-order vector.
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// The layer strains of a z-normal laminate (layer stiffnesses @p L, volume
/// fractions @p c summing to 1) under macro strain @p E and an eigenstrain
/// @p mu per layer (all lamina order, engineering shear).
inline std::vector<Vec6> laminateLayerStrains(const std::vector<materials::Matrix6>& L,
                                              const std::vector<double>& c, const Vec6& E,
                                              const std::vector<Vec6>& mu) {
  const std::array<int, 3> t{0, 1, 3}, n{2, 4, 5};
  const std::size_t layers = L.size();
  std::vector<Eigen::Matrix3d> N(layers);
  std::vector<Eigen::Vector3d> g(layers); // eps_n = N (s + g)
  Eigen::Matrix3d sumN = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = E({2, 4, 5});
  for (std::size_t a = 0; a < layers; ++a) {
    Eigen::Matrix3d Lnn, Lnt;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Lnn(i, j) = L[a](n[static_cast<std::size_t>(i)], n[static_cast<std::size_t>(j)]);
        Lnt(i, j) = L[a](n[static_cast<std::size_t>(i)], t[static_cast<std::size_t>(j)]);
      }
    N[a] = Lnn.inverse();
    const Vec6 Lmu = L[a] * mu[a];
    g[a] = -Lnt * E({0, 1, 3}) + Lmu({2, 4, 5});
    sumN += c[a] * N[a];
    rhs -= c[a] * N[a] * g[a];
  }
  const Eigen::Vector3d s = sumN.inverse() * rhs;
  std::vector<Vec6> eps(layers);
  for (std::size_t a = 0; a < layers; ++a) {
    eps[a] = E;
    const Eigen::Vector3d en = N[a] * (s + g[a]);
    for (int i = 0; i < 3; ++i)
      eps[a](n[static_cast<std::size_t>(i)]) = en(i);
  }
  return eps;
}

/// The exact reduced-order matrices of that laminate, one partition per
/// layer: @p A[a] and @p P[b * layers + a] as in materials/reduced_order.hpp.
inline void laminateReducedOrder(const std::vector<materials::Matrix6>& L,
                                 const std::vector<double>& c, std::vector<materials::Matrix6>& A,
                                 std::vector<materials::Matrix6>& P) {
  const std::size_t layers = L.size();
  A.assign(layers, materials::Matrix6::Zero());
  P.assign(layers * layers, materials::Matrix6::Zero());
  const std::vector<Vec6> no_mu(layers, Vec6::Zero());
  for (int k = 0; k < 6; ++k) {
    const auto eps = laminateLayerStrains(L, c, Vec6::Unit(k), no_mu);
    for (std::size_t a = 0; a < layers; ++a)
      A[a].col(k) = eps[a];
  }
  for (std::size_t a = 0; a < layers; ++a)
    for (int J = 0; J < 6; ++J) {
      std::vector<Vec6> mu = no_mu;
      mu[a] = Vec6::Unit(J);
      const auto eps = laminateLayerStrains(L, c, Vec6::Zero(), mu);
      for (std::size_t b = 0; b < layers; ++b)
        P[b * layers + a].col(J) = eps[b];
    }
}

/// The clustering interaction tensors of that laminate (homogenize/
/// cluster_interaction.hpp), one partition per layer, by hand: the
/// indicator of a z-normal layer has transforms on the z axis only, where
/// the unit wave vector is +-e_z, so G^(ab) = Gamma(e_z) (delta_ab - c_b)
/// (the sum of conj(chi_a) chi_b over the nonzero modes is N^2 (c_a delta_ab
/// - c_a c_b)), and in lamina order with engineering rows Gamma_a(e_z) =
/// diag(0, 0, 1, 0, 1, 1) (zzzz, and yzyz, xzxz with the factor 4 of two
/// shear indices over the 1/4), Gamma_b(e_z) = e_zz e_zz^T: the
/// one-dimensional answers 1 / (lambda0 + 2 mu0) for tau_zz and 1 / mu0 for
/// a transverse shear.
inline void laminateInteractions(const std::vector<double>& c, std::vector<materials::Matrix6>& Ga,
                                 std::vector<materials::Matrix6>& Gb) {
  const std::size_t layers = c.size();
  materials::Matrix6 a = materials::Matrix6::Zero(), b = materials::Matrix6::Zero();
  a(2, 2) = a(4, 4) = a(5, 5) = 1;
  b(2, 2) = 1;
  Ga.assign(layers * layers, materials::Matrix6::Zero());
  Gb.assign(layers * layers, materials::Matrix6::Zero());
  for (std::size_t I = 0; I < layers; ++I)
    for (std::size_t J = 0; J < layers; ++J) {
      const double w = (I == J ? 1.0 : 0.0) - c[J];
      Ga[I * layers + J] = w * a;
      Gb[I * layers + J] = w * b;
    }
}

} // namespace lamina::test
