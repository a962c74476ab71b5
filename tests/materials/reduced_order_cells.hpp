#pragma once
/// @file reduced_order_cells.hpp
/// @brief Test cells for the reduced-order law: z-normal laminates with the
/// exact A and P of laminate_reduced_order.hpp (one partition per layer), a
/// GVBO soft phase with the catalog's polyurea-soft parameters (polyurea
/// chapter, Table 11) and an elastic hard phase (E 890 MPa, nu 0.491).

#include "laminate_reduced_order.hpp"
#include "materials/law.hpp"
#include "materials/law_spec.hpp"
#include "materials/library.hpp"
#include "materials/reduced_order.hpp"

#include <Eigen/Core>

#include <random>
#include <vector>

namespace lamina::test {

/// The soft domains of the chapter's Table 11 (catalog polyurea-soft), SI.
inline materials::LawSpec softGvbo() {
  materials::GvboParameters p;
  p.E0 = 156e6;
  p.nu0 = 0.494;
  p.Et = 23.3e6;
  p.p = -6;
  p.a1 = 0;
  p.a2 = 10e6;
  p.a3 = 0;
  p.k1 = 17;
  p.k2 = 0.47e6;
  p.k3 = 1.47e6;
  p.k4 = 4;
  p.Em = 13600e6;
  p.A0 = 1e6;
  p.Ac = 0;
  p.Af = 0;
  materials::LawSpec s;
  s.kind = materials::LawKind::Gvbo;
  s.C = materials::Stiffness::isotropic(p.E0, p.nu0);
  s.gvbo = p;
  return s;
}

/// The hard domains of Table 11: isotropic, E 890 MPa, nu 0.491.
inline materials::LawSpec hardElastic() {
  materials::LawSpec s;
  s.kind = materials::LawKind::Isotropic;
  s.C = materials::Stiffness::isotropic(890e6, 0.491);
  return s;
}

/// A z-normal laminate of @p layers (the law of layer a is @p phases[layer_phase[a]])
/// with fractions @p c, one partition per layer: A, P exact, R and Q zero
/// unless @p synthetic_micro_inertia (then R = G G^T with G random, a
/// positive semi-definite Gram matrix as eq. 40 makes it, and Q random, both
/// of order 1e-6 kg/m), C = sum c L0 A, density the mean.
inline materials::ReducedOrderModel laminateCell(const std::vector<materials::LawSpec>& phases,
                                                 const std::vector<int>& layer_phase,
                                                 const std::vector<double>& c,
                                                 bool synthetic_micro_inertia = false) {
  materials::ReducedOrderModel m;
  const double rho[2] = {1100, 1200};
  for (std::size_t p = 0; p < phases.size(); ++p)
    m.phases.push_back({p == 0 ? "soft" : "hard", phases[p], rho[p % 2]});
  std::vector<materials::Matrix6> L;
  for (std::size_t a = 0; a < layer_phase.size(); ++a) {
    m.partition_phase.push_back(layer_phase[a]);
    L.push_back(phases[static_cast<std::size_t>(layer_phase[a])].C.matrix());
  }
  m.fraction = c;
  laminateReducedOrder(L, c, m.A, m.P);
  const auto n = static_cast<Eigen::Index>(6 * c.size());
  m.R = Eigen::MatrixXd::Zero(n, n);
  m.Q = Eigen::MatrixXd::Zero(6, n);
  if (synthetic_micro_inertia) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::MatrixXd G(n, n), Q(6, n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        G(i, j) = u(rng);
    for (Eigen::Index i = 0; i < 6; ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        Q(i, j) = u(rng);
    m.R = 1e-6 * G * G.transpose();
    m.Q = 1e-6 * Q;
    m.D_lin = 1e-6 * materials::Matrix6::Identity();
  }
  m.C.setZero();
  m.density = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    m.C += c[a] * L[a] * m.A[a];
    m.density += c[a] * m.phases[static_cast<std::size_t>(layer_phase[a])].density;
  }
  return m;
}

/// The chapter's two-domain laminate: GVBO soft 0.81, elastic hard 0.19,
/// one partition per layer.
inline materials::ReducedOrderModel polyureaLaminate(bool synthetic_micro_inertia = false) {
  return laminateCell({softGvbo(), hardElastic()}, {0, 1}, {0.81, 0.19}, synthetic_micro_inertia);
}

/// @p m (a laminate of laminateCell) with the clustering scheme: the
/// interaction tensors of its layers (laminateInteractions).
inline materials::ReducedOrderModel clustering(materials::ReducedOrderModel m) {
  m.scheme = materials::ReducedOrderScheme::Clustering;
  laminateInteractions(m.fraction, m.Ga, m.Gb);
  return m;
}

/// Drives @p law from its initial state along eps = E i / @p steps (i = 1..steps,
/// small strain: J = 1 + tr eps), @p dt per step, into @p state; @return the final strain.
inline Vec6 loadAlong(const materials::ConstitutiveLaw& law, const Vec6& E, int steps, double dt,
                      std::vector<double>& state) {
  state.assign(static_cast<std::size_t>(law.stateSize()), 0.0);
  law.initState(state.data());
  Vec6 eps = Vec6::Zero(), sigma;
  for (int i = 1; i <= steps; ++i) {
    const Vec6 next = E * i / steps;
    const materials::PointStep s{eps, next, 1 + eps.head<3>().sum(), 1 + next.head<3>().sum(), dt};
    law.update(s, state.data(), state.data(), sigma, nullptr);
    eps = next;
  }
  return eps;
}

/// The library entry of @p model named @p name (kind "reduced-order", its
/// phases, C and density; side file and checksum set by Library::add).
inline materials::Material reducedOrderEntry(const std::string& name,
                                             const materials::ReducedOrderModel& model) {
  materials::Material m;
  m.name = name;
  m.kind = materials::kReducedOrderKind;
  m.C = materials::Stiffness(model.C);
  m.density = model.density;
  m.phases = model.phases;
  m.provenance.insert("program", "test");
  return m;
}

/// Adds @p model to the library at @p library as entry @p name, its arrays
/// in a side file written by writeReducedOrderArrays.
inline void addReducedOrderEntry(const std::filesystem::path& library, const std::string& name,
                                 const materials::ReducedOrderModel& model) {
  materials::Library(library).add(
      reducedOrderEntry(name, model), false,
      [&model](const std::filesystem::path& h5) { materials::writeReducedOrderArrays(h5, model); });
}

} // namespace lamina::test
