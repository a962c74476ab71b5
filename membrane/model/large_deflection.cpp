#include "membrane/model/large_deflection.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/parallel.hpp"
#include "membrane/model/law_lanes.hpp"
#include "membrane/model/law_point.hpp"
#include "membrane/model/relaxed_wrinkling.hpp"
#include "membrane/model/stable_step.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace lamina::membrane {

namespace {
/// Below this many elements the loops run on one thread.
constexpr int kParallelElements = 4000;

/// Whether Linear groups take the lanes (LargeDeflection::useLanes).
bool g_lanes = true;

/// @return the larger eigenvalue of the symmetric [a c; c b]: principal2()'s
/// major value without its hypot (which guards against overflow at extreme
/// exponents, at several times the cost), for the stable step's two per
/// element
double majorValue(double a, double b, double c) {
  const double h = 0.5 * (a - b);
  return 0.5 * (a + b) + std::sqrt(h * h + c * c);
}
} // namespace

LargeDeflection::LargeDeflection(const Body& body) : body_(body) {
  const auto t0 = std::chrono::steady_clock::now();
  const Mesh& mesh = body.mesh;
  const int ne = mesh.numElements(), n = mesh.numNodes();
  for (const auto& s : body.sections) {
    cps_.push_back(planeStressStiffness(s.D));
    cps_inv_.push_back(cps_.back().inverse());
    s0_.push_back(s.prestress / s.thickness);
    LAMINA_CHECK(s.isLinear() || s.prestress.isZero(), "section '", s.name, "' (", s.material,
                 "): a pre-stress needs a linear elastic law (a nonlinear law starts unstressed)");
    relaxed_.push_back(s.isLinear() && s.wrinklingLaw() == WrinklingLaw::Relaxed ? 1 : 0);
    any_projection_ =
        any_projection_ || (s.isLinear() && s.wrinklingLaw() == WrinklingLaw::Projection);
    any_threshold_ =
        any_threshold_ || std::isfinite(s.failure_strain) || std::isfinite(s.failure_stress);
  }
  elements_.reserve(ne);
  for (int e = 0; e < ne; ++e)
    elements_.push_back(makeFabricElement(mesh, e, body.sections[mesh.region_of[e]].axis));
  packed_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const FabricElement& el = elements_[e];
    const int r = mesh.region_of[e];
    Packed& p = packed_[e];
    for (int a = 0; a < 3; ++a) {
      p.node[a] = el.nodes[a];
      p.dN[2 * a] = el.dN[a].x();
      p.dN[2 * a + 1] = el.dN[a].y();
    }
    // The general path: the projection law or a nonlinear law.
    const Section& s = body.sections[r];
    p.region = !s.isLinear() || s.wrinklingLaw() == WrinklingLaw::Projection ? -1 - r : r;
    p.hA = body.sections[r].thickness * el.area0;
  }
  x0_.resize(3 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    Eigen::Map<Eigen::Vector3d>(x0_.data() + 3 * static_cast<size_t>(i)) = mesh.point(i);
  // Lumped mass: rho h A0 / 3 per node, plus the point masses.
  Eigen::VectorXd m = Eigen::VectorXd::Zero(n);
  for (int e = 0; e < ne; ++e) {
    const auto& s = body.sections[mesh.region_of[e]];
    for (int i : mesh.triangles[e])
      m[i] += s.density * s.thickness * elements_[e].area0 / 3;
  }
  for (const auto& [node, pm] : body.point_masses)
    m[node] += pm;
  M_.resize(3 * n, 3 * n);
  M_.reserve(Eigen::VectorXi::Constant(3 * n, 1));
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      M_.insert(3 * i + c, 3 * i + c) = m[i];
  M_.makeCompressed();
  for (size_t r = 0; r < body.sections.size(); ++r) {
    wave_modulus_.push_back(maxWaveModulus(cps_[r], StrainKind::PlaneStress));
    rest_speed_.push_back(restSpeed(r));
  }
  length_.resize(ne);
  min_length_.assign(body.sections.size(), std::numeric_limits<double>::infinity());
  for (int e = 0; e < ne; ++e) {
    length_[e] = elementLength(mesh, e);
    double& l = min_length_[static_cast<size_t>(mesh.region_of[e])];
    l = std::min(l, length_[e]);
  }
  initHistory();
  initLanes();
  setup_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

FabricStress LargeDeflection::stress(int e, const Eigen::VectorXd& u) const {
  const FabricElement& el = elements_[e];
  const int r = body_.mesh.region_of[e];
  std::array<Eigen::Vector3d, 3> x;
  for (int a = 0; a < 3; ++a)
    x[a] = body_.mesh.point(el.nodes[a]) + u.segment<3>(3 * el.nodes[a]);
  if (const double* b = history(e)) {
    FabricStress st = fabricStress(el, x, cps_[r], s0_[r], WrinklingLaw::None); // F and E
    st.S = lawPointPk2(st.F, b);
    st.state = static_cast<Wrinkle>(static_cast<int>(b[LawPoint::kWrinkleState]));
    return st;
  }
  return fabricStress(el, x, cps_[r], s0_[r], body_.sections[r].wrinklingLaw());
}

void LargeDeflection::initHistory() {
  const Mesh& mesh = body_.mesh;
  const int ne = mesh.numElements();
  long size = 0;
  std::vector<long> offset(ne, -1);
  for (int e = 0; e < ne; ++e) {
    const Section& s = body_.sections[mesh.region_of[e]];
    if (s.isLinear())
      continue;
    offset[e] = size;
    size += LawPoint::size(*s.law);
  }
  if (size == 0)
    return;
  history_offset_ = std::move(offset);
  history_.assign(static_cast<size_t>(size), 0.0);
  for (int e = 0; e < ne; ++e)
    if (history_offset_[e] >= 0)
      initLawPoint(*body_.sections[mesh.region_of[e]].law, elements_[e].frame.leftCols<2>(),
                   history_.data() + history_offset_[e]);
  trial_ = history_;
}

void LargeDeflection::useLanes(bool lanes) {
  g_lanes = lanes;
}

void LargeDeflection::initLanes() {
  static_assert(kFabricLanes == kLawLanes, "one group size for every kind of lanes");
  const Mesh& mesh = body_.mesh;
  const int ne = mesh.numElements(), ng = (ne + kLawLanes - 1) / kLawLanes;
  lane_groups_.assign(static_cast<size_t>(ng), LaneGroup{});
  lane_elements_.resize(static_cast<size_t>(ng));
  for (int g = 0; g < ng; ++g) {
    const int e0 = g * kLawLanes, e1 = std::min(ne, e0 + kLawLanes), r = mesh.region_of[e0];
    bool same = true;
    for (int e = e0; e < e1; ++e)
      same = same && mesh.region_of[e] == r;
    LaneGroup& group = lane_groups_[static_cast<size_t>(g)];
    if (same && packed_[e0].region >= 0 && e1 - e0 == kLawLanes)
      group = {LaneKind::Linear, r};
    else if (same && hasHistory() && history_offset_[e0] >= 0 &&
             dynamic_cast<const materials::GvboLaw*>(body_.sections[r].law.get()) != nullptr)
      group = {LaneKind::Gvbo, r};
    FabricLaneGroup& lanes = lane_elements_[static_cast<size_t>(g)];
    for (int k = 0; k < kLawLanes; ++k) {
      const Packed& p = packed_[std::min(e0 + k, e1 - 1)]; // unused lanes repeat the last element
      for (int a = 0; a < 3; ++a)
        lanes.node[a][k] = 3 * p.node[a];
      for (int j = 0; j < 6; ++j)
        lanes.dN[j][k] = p.dN[j];
      lanes.hA[k] = p.hA;
    }
  }
  lane_laws_.resize(body_.sections.size());
  for (size_t r = 0; r < body_.sections.size(); ++r) {
    LinearLaneLaw& law = lane_laws_[r];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        law.C[i][j] = cps_[r](i, j);
      law.s0[i] = s0_[r][i];
    }
    law.relaxed = relaxed_[r] != 0;
  }
}

void LargeDeflection::lawLaneForces(int e0, int n, int r, const double* x, double (*out)[9]) const {
  const Section& s = body_.sections[r];
  const auto& law = static_cast<const materials::GvboLaw&>(*s.law);
  LawLaneStep io;
  double pad[LawPoint::kLaw + materials::GvboState::kSize]; // the history of an unused lane
  for (int k = 0; k < kLawLanes; ++k) {
    const int e = e0 + std::min(k, n - 1); // unused lanes repeat the last element
    const Packed& p = packed_[e];
    double F0[3], F1[3];
    deformation(p, x, F0, F1);
    for (int c = 0; c < 3; ++c) {
      io.F[c][k] = F0[c];
      io.F[3 + c][k] = F1[c];
    }
    for (int j = 0; j < 6; ++j)
      io.dN[j][k] = p.dN[j];
    io.hA[k] = p.hA;
    const long o = history_offset_[e];
    io.block_n[k] = history_.data() + o;
    io.block[k] = k < n ? trial_.data() + o : pad;
  }
  // the next group's history blocks are contiguous with these: fetch them
  // while this group computes (the step is otherwise bound by their latency)
  if (e0 + 2 * kLawLanes <= static_cast<int>(history_offset_.size())) {
    const long o0 = history_offset_[e0 + kLawLanes], o1 = history_offset_[e0 + 2 * kLawLanes - 1];
    const long end = std::min(o1 + LawPoint::size(law), static_cast<long>(history_.size()));
    if (o0 >= 0 && o1 > o0)
      for (long o = o0; o < end; o += 8) { // 8 doubles: one cache line
        __builtin_prefetch(history_.data() + o, 0);
        __builtin_prefetch(trial_.data() + o, 1);
      }
  }
  const unsigned taken = stepGvboLawPoints(law, s.tension_only, step_dt_, io);
  for (int k = 0; k < n; ++k) {
    if (taken >> k & 1u) {
      for (int j = 0; j < 9; ++j)
        out[k][j] = io.f[j][k];
      continue;
    }
    Eigen::Matrix<double, 3, 2> F;
    for (int c = 0; c < 3; ++c) {
      F(c, 0) = io.F[c][k];
      F(c, 1) = io.F[3 + c][k];
    }
    lawElementForce(e0 + k, F, out[k]);
  }
}

void LargeDeflection::lawElementForce(int e, const Eigen::Matrix<double, 3, 2>& F,
                                      double* out) const {
  const int r = body_.mesh.region_of[e];
  const Section& s = body_.sections[r];
  const long o = history_offset_[e];
  Eigen::Vector3d S;
  try {
    S = stepLawPoint(*s.law, F, s.tension_only, step_dt_, history_.data() + o, trial_.data() + o);
  } catch (const Error& err) {
    throw DivergenceError("element " + std::to_string(body_.mesh.elementLabel(e)) + " (section '" +
                          s.name + "', " + s.material + ") at t = " + core::formatShort(step_t1_) +
                          " s: " + err.message());
  }
  Eigen::Matrix2d Sm;
  Sm << S[0], S[2], S[2], S[1];
  const Eigen::Matrix<double, 3, 2> P = (s.thickness * elements_[e].area0) * (F * Sm);
  for (int a = 0; a < 3; ++a)
    Eigen::Map<Eigen::Vector3d>(out + 3 * a) = P * elements_[e].dN[a];
}

Eigen::Vector2d LargeDeflection::cauchyPrincipal(int e, const FabricStress& st) const {
  if (const double* b = history(e)) // the law's Cauchy stress (its thickness follows it)
    return principal2(b[LawPoint::kSigma], b[LawPoint::kSigma + 1], b[LawPoint::kSigma + 2]);
  return principalCauchy(st);
}

double LargeDeflection::inelasticDissipation() const {
  double D = 0;
  const int ne = body_.mesh.numElements();
  for (int e = 0; e < ne; ++e)
    if (const double* b = history(e))
      D += body_.sections[body_.mesh.region_of[e]].thickness * elements_[e].area0 *
           b[LawPoint::kDissipation];
  return D;
}

namespace {
constexpr const char* kHistoryKey = "structure/law_history";
} // namespace

void LargeDeflection::saveHistory(History& h) const {
  if (hasHistory())
    h[kHistoryKey] = Eigen::Map<const Eigen::VectorXd>(history_.data(),
                                                       static_cast<Eigen::Index>(history_.size()));
}

void LargeDeflection::restoreHistory(const History& h) {
  if (!hasHistory()) {
    if (h.count(kHistoryKey))
      throw Error(std::string("checkpoint has an entry '") + kHistoryKey +
                  "' but no section of this case has a nonlinear law");
    return;
  }
  const Eigen::VectorXd& v =
      historyEntry(h, kHistoryKey, static_cast<Eigen::Index>(history_.size()));
  if (!v.allFinite())
    throw Error(std::string("checkpoint entry '") + kHistoryKey + "' holds a non-finite value");
  for (int e = 0; e < body_.mesh.numElements(); ++e) {
    const long o = history_offset_[e];
    if (o < 0)
      continue;
    const double lambda3 = v[o + LawPoint::kLambda3], J = v[o + LawPoint::kJ],
                 w = v[o + LawPoint::kWrinkleState];
    if (!(lambda3 > 0 && J > 0 && (w == 0 || w == 1 || w == 2)))
      throw Error(std::string("checkpoint entry '") + kHistoryKey + "': element " +
                  std::to_string(e) + " has a thickness stretch " + core::formatShort(lambda3) +
                  ", J " + core::formatShort(J) + " and wrinkling state " + core::formatShort(w) +
                  " (need > 0, > 0 and 0, 1 or 2)");
  }
  std::copy(v.data(), v.data() + v.size(), history_.begin());
  trial_ = history_;
}

const double* LargeDeflection::positions(const Eigen::VectorXd& u) const {
  const int n = static_cast<int>(u.size());
  x_.resize(u.size());
  double* x = x_.data();
  const double *x0 = x0_.data(), *up = u.data();
#pragma omp parallel for schedule(static) if (n > 3 * kParallelElements)
  for (int i = 0; i < n; ++i)
    x[i] = x0[i] + up[i];
  return x;
}

void LargeDeflection::deformation(const Packed& p, const double* x, double (&F0)[3],
                                  double (&F1)[3]) const {
  for (int c = 0; c < 3; ++c)
    F0[c] = F1[c] = 0;
  for (int a = 0; a < 3; ++a) {
    const size_t k = 3 * static_cast<size_t>(p.node[a]);
    for (int c = 0; c < 3; ++c) {
      F0[c] += x[k + c] * p.dN[2 * a];
      F1[c] += x[k + c] * p.dN[2 * a + 1];
    }
  }
}

// One function for the one-element force and stable step; the lanes
// (fabric_lanes.cpp) repeat its sums in its order.
Eigen::Vector3d LargeDeflection::linearStress(int r, const double (&F0)[3], const double (&F1)[3],
                                              double (&C)[3]) const {
  C[0] = F0[0] * F0[0] + F0[1] * F0[1] + F0[2] * F0[2];
  C[1] = F1[0] * F1[0] + F1[1] * F1[1] + F1[2] * F1[2];
  C[2] = F0[0] * F1[0] + F0[1] * F1[1] + F0[2] * F1[2];
  const Eigen::Vector3d E(0.5 * (C[0] - 1), 0.5 * (C[1] - 1), C[2]);
  // S = C_ps E + S0 summed as Eigen sums its fixed-size product (rows 0 and
  // 1 left to right, row 2 pairing its last two terms), which this function
  // used before the lanes (fabric_lanes.cpp) repeated it: results unchanged
  const Eigen::Matrix3d& K = cps_[r];
  const Eigen::Vector3d& S0 = s0_[r];
  Eigen::Vector3d S(K(0, 0) * E[0] + K(0, 1) * E[1] + K(0, 2) * E[2] + S0[0],
                    K(1, 0) * E[0] + K(1, 1) * E[1] + K(1, 2) * E[2] + S0[1],
                    (K(2, 0) * E[0] + (K(2, 1) * E[1] + K(2, 2) * E[2])) + S0[2]);
  if (relaxed_[static_cast<size_t>(r)] && !positiveSemidefinite2(S[0], S[1], S[2]))
    S = relaxedStress(S, E + cps_inv_[r] * s0_[r], cps_[r]).S;
  return S;
}

void LargeDeflection::elementForce(int e, const double* x, const Eigen::VectorXd& u, double* out,
                                   core::ParallelErrors& errors) const {
  // fabric_element.hpp written out for the elastic element, from the packed
  // data: F = sum x_a dN_a^T, E = (F^T F - I)/2, S = C_ps E + S0,
  // f_a = h A0 F S dN_a; with the relaxed wrinkling law, S is relaxed when it
  // is not taut (relaxed_wrinkling.hpp). Projection and nonlinear-law regions
  // take the general path.
  const Packed& p = packed_[e];
  const bool law_element = p.region < 0 && hasHistory() && history_offset_[e] >= 0;
  if (p.region < 0 && !law_element) {
    const FabricStress st = stress(e, u);
    Eigen::Map<Eigen::Matrix3d>{out} =
        fabricForces(elements_[e], st, body_.sections[-1 - p.region].thickness);
    return;
  }
  double F0[3], F1[3]; // columns of F
  deformation(p, x, F0, F1);
  if (law_element) {
    Eigen::Matrix<double, 3, 2> F;
    F << F0[0], F1[0], F0[1], F1[1], F0[2], F1[2];
    errors.run([&] { lawElementForce(e, F, out); });
    return;
  }
  double C[3];
  const Eigen::Vector3d S = linearStress(p.region, F0, F1, C);
  double P0[3], P1[3]; // h A0 F S, columns
  for (int c = 0; c < 3; ++c) {
    P0[c] = p.hA * (F0[c] * S[0] + F1[c] * S[2]);
    P1[c] = p.hA * (F0[c] * S[2] + F1[c] * S[1]);
  }
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      out[3 * a + c] = P0[c] * p.dN[2 * a] + P1[c] * p.dN[2 * a + 1];
}

void LargeDeflection::groupForces(int g, const double* x, const Eigen::VectorXd& u, double* f,
                                  core::ParallelErrors& errors) const {
  const int ne = body_.mesh.numElements(), e0 = g * kLawLanes, n = std::min(kLawLanes, ne - e0);
  const int* corner = plan_.corner.data();
  double* deferred = plan_.deferred_f.data();
  auto add = [&](int e, const double* out) { // each corner's force to its node or its place
    for (int a = 0; a < 3; ++a) {
      const int code = corner[3 * static_cast<size_t>(e) + a];
      if (code >= 0)
        for (int c = 0; c < 3; ++c)
          f[3 * static_cast<size_t>(code) + c] += out[3 * a + c];
      else
        for (int c = 0; c < 3; ++c)
          deferred[3 * static_cast<size_t>(-1 - code) + c] = out[3 * a + c];
    }
  };
  const LaneGroup group = lane_groups_[static_cast<size_t>(g)];
  if (group.kind == LaneKind::Linear && g_lanes) { // a full group
    double lanes[9][kFabricLanes];
    const std::uint32_t taken =
        linearFabricForces(lane_laws_[static_cast<size_t>(group.region)],
                           lane_elements_[static_cast<size_t>(g)], x, lanes);
    for (int k = 0; k < kFabricLanes; ++k) {
      double out[9];
      for (int j = 0; j < 9; ++j)
        out[j] = lanes[j][k];
      if (!(taken >> k & 1u))
        elementForce(e0 + k, x, u, out, errors);
      add(e0 + k, out);
    }
    return;
  }
  double out[kLawLanes][9] = {}; // stays zero when a law's failure is recorded in errors
  if (group.kind == LaneKind::Gvbo)
    errors.run([&] { lawLaneForces(e0, n, group.region, x, out); });
  else
    for (int k = 0; k < n; ++k)
      elementForce(e0 + k, x, u, out[k], errors);
  for (int k = 0; k < n; ++k)
    add(e0 + k, out[k]);
}

void LargeDeflection::planCorners(int threads) const {
  const Mesh& mesh = body_.mesh;
  const int ne = mesh.numElements(), n = mesh.numNodes();
  const int ng = static_cast<int>(lane_groups_.size());
  plan_.threads = 0; // built in plan, swapped in at the end
  CornerPlan plan;
  plan.corner.assign(3 * static_cast<size_t>(ne), 0);
  std::vector<int> first(static_cast<size_t>(n), -1); // the thread of each node's first element
  std::vector<std::pair<int, int>> later;             // (node, corner) of the other threads
  for (int t = 0; t < threads; ++t) {
    const auto [g0, g1] = core::shareRange(ng, t, threads); // as core::threadRange in the team
    for (int e = std::min(ne, kLawLanes * g0); e < std::min(ne, kLawLanes * g1); ++e)
      for (int a = 0; a < 3; ++a) {
        const int i = mesh.triangles[e][a];
        if (first[i] < 0)
          first[i] = t;
        plan.corner[3 * static_cast<size_t>(e) + a] = i;
        if (first[i] != t)
          later.emplace_back(i, 3 * e + a);
      }
  }
  // deferred places node by node, each node's corners in element order
  std::stable_sort(later.begin(), later.end(),
                   [](const auto& p, const auto& q) { return p.first < q.first; });
  plan.deferred_start.assign(1, 0);
  for (size_t k = 0; k < later.size(); ++k) {
    if (k == 0 || later[k].first != later[k - 1].first) {
      if (k > 0)
        plan.deferred_start.push_back(static_cast<int>(k));
      plan.deferred_node.push_back(later[k].first);
    }
    plan.corner[static_cast<size_t>(later[k].second)] = -1 - static_cast<int>(k);
  }
  if (!later.empty())
    plan.deferred_start.push_back(static_cast<int>(later.size()));
  plan.deferred_f.assign(3 * later.size(), 0.0);
  plan.threads = threads;
  plan_ = std::move(plan);
}

void LargeDeflection::internalForce(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  const int ne = body_.mesh.numElements(), n3 = 3 * body_.mesh.numNodes();
  core::ParallelErrors errors; // a nonlinear law's failure, naming the element
  f.resize(n3);
  x_.resize(static_cast<size_t>(n3));
  double *x = x_.data(), *fp = f.data();
  const double *x0 = x0_.data(), *up = u.data();
  // Threads only pay off on large meshes (on small ones their start-up dominates).
#pragma omp parallel if (ne > kParallelElements)
  {
#pragma omp single nowait
    if (plan_.threads != omp_get_num_threads())
      errors.run([&] { planCorners(omp_get_num_threads()); });
#pragma omp for schedule(static)
    for (int i = 0; i < n3; ++i) {
      x[i] = x0[i] + up[i];
      fp[i] = 0;
    }
    // Each thread its share of the groups, in element order (planCorners).
    const auto [g0, g1] = core::threadRange(static_cast<int>(lane_groups_.size()));
    if (!errors.failed())
      for (int g = g0; g < g1; ++g)
        groupForces(g, x, u, fp, errors);
#pragma omp barrier
    const int nd = errors.failed() ? 0 : static_cast<int>(plan_.deferred_node.size());
#pragma omp for schedule(static)
    for (int k = 0; k < nd; ++k) { // the later threads' corners, in element order
      double* fi = fp + 3 * static_cast<size_t>(plan_.deferred_node[k]);
      for (int d = plan_.deferred_start[k]; d < plan_.deferred_start[k + 1]; ++d)
        for (int c = 0; c < 3; ++c)
          fi[c] += plan_.deferred_f[3 * static_cast<size_t>(d) + c];
    }
  }
  errors.rethrow();
}

double LargeDeflection::strainEnergy(const Eigen::VectorXd& u) const {
  const int ne = body_.mesh.numElements();
  double U = 0;
#pragma omp parallel for reduction(+ : U) schedule(static) if (ne > kParallelElements)
  for (int e = 0; e < ne; ++e) {
    const int r = body_.mesh.region_of[e];
    if (const double* b = history(e)) {
      U += body_.sections[r].thickness * elements_[e].area0 * b[LawPoint::kPsi];
      continue;
    }
    const FabricStress st = stress(e, u);
    const double w = body_.sections[r].tension_only
                         ? fabricStoredEnergy(st, cps_inv_[r], s0_[r])
                         : 0.5 * st.E.dot(cps_[r] * st.E) + s0_[r].dot(st.E);
    U += body_.sections[r].thickness * elements_[e].area0 * w;
  }
  return U;
}

double LargeDeflection::restSpeed(size_t r) const {
  // A tension T adds T / (rho h) to c^2 (the string's wave); take its largest principal value.
  const Eigen::Vector2d t = principal2(s0_[r][0], s0_[r][1], s0_[r][2]);
  return std::sqrt((wave_modulus_[r] + std::max(t[0], 0.0)) / body_.sections[r].density);
}

double LargeDeflection::stableStep() const {
  return criticalStep(body_.mesh, rest_speed_);
}

double LargeDeflection::currentStableStep(const Eigen::VectorXd& u) const {
  const size_t nr = body_.sections.size();
  std::vector<double> jmin(nr, std::numeric_limits<double>::infinity()), jmax(nr, 0.0);
  std::vector<double> amp(nr, 1.0), tension(nr, 0.0);
  for (int e = 0; e < body_.mesh.numElements() && hasHistory(); ++e)
    if (const double* b = history(e)) {
      const auto r = static_cast<size_t>(body_.mesh.region_of[e]);
      const double J = b[LawPoint::kJ];
      jmin[r] = std::min(jmin[r], J);
      jmax[r] = std::max(jmax[r], J);
      // Per reference length and mass the stiffness of the Cauchy moduli is
      // J C / lambda_min^2 (lambda_min the least in-plane stretch), and a
      // tension s1 adds J s1 / lambda_min^2 (the string's wave).
      const Eigen::Map<const Eigen::Matrix<double, 3, 2>> F(b + LawPoint::kF);
      const Eigen::Matrix2d C = F.transpose() * F;
      const double l2 = principal2(C(0, 0), C(1, 1), C(0, 1))[1];
      const double s1 =
          principal2(b[LawPoint::kSigma], b[LawPoint::kSigma + 1], b[LawPoint::kSigma + 2])[0];
      amp[r] = std::max(amp[r], J / l2);
      tension[r] = std::max(tension[r], J * std::max(s1, 0.0) / l2);
    }
  double dt = linearStableStep(u);
  for (size_t r = 0; r < nr; ++r) {
    const Section& s = body_.sections[r];
    if (s.isLinear())
      continue;
    // The instantaneous stiffness is the fastest the law can respond (any
    // rate); it changes with J. Reference mass and length: scaled by the
    // largest J / lambda_min^2 of the region, plus its largest tension term.
    double modulus = 0;
    const double lo = std::min(jmin[r], 1.0), hi = std::max(jmax[r], 1.0);
    for (int k = 0; k <= 8; ++k) {
      const double J = lo + (hi - lo) * k / 8.0;
      const Eigen::Matrix3d c = planeStressStiffness(s.law->elasticStiffness(J).matrix());
      modulus = std::max(modulus, maxWaveModulus(c, StrainKind::PlaneStress));
    }
    dt = std::min(dt, min_length_[r] / std::sqrt((amp[r] * modulus + tension[r]) / s.density));
  }
  return dt;
}

double LargeDeflection::elementStableStep(int e, const double* x, const Eigen::VectorXd& u) const {
  // P = F S with S = C_ps E + S0 has dP/dF = S + F C_ps F^T: per reference
  // length and mass the fastest wave's modulus is M(C_ps) lambda_max^2 plus
  // the largest principal S (the string's wave of a tension).
  const int r = body_.mesh.region_of[e];
  const Section& s = body_.sections[r];
  double F0[3], F1[3]; // columns of F
  deformation(packed_[e], x, F0, F1);
  double C[3]; // C = F^T F: C11, C22, C12
  Eigen::Vector3d S = linearStress(r, F0, F1, C);
  if (s.tension_only && !relaxed_[static_cast<size_t>(r)] &&
      !positiveSemidefinite2(S[0], S[1], S[2]))
    S = stress(e, u).S; // the projection law's tension-only stress
  const double stretch = std::max(majorValue(C[0], C[1], C[2]), 1.0);
  const double tension = std::max(majorValue(S[0], S[1], S[2]), 0.0);
  const double now = std::sqrt((stretch * wave_modulus_[r] + tension) / s.density);
  const double rest = rest_speed_[r];
  return length_[e] / (now > rest * (1 + 1e-12) ? now : rest);
}

double LargeDeflection::linearStableStep(const Eigen::VectorXd& u) const {
  const int ne = body_.mesh.numElements(), ng = static_cast<int>(lane_groups_.size());
  double dt = std::numeric_limits<double>::infinity();
  const double* x = positions(u);
#pragma omp parallel for schedule(static) reduction(min : dt) if (ne > kParallelElements)
  for (int g = 0; g < ng; ++g) {
    const int e0 = g * kFabricLanes, n = std::min(kFabricLanes, ne - e0);
    const LaneGroup group = lane_groups_[static_cast<size_t>(g)];
    std::uint32_t taken = 0;
    double lanes[kFabricLanes];
    if (group.kind == LaneKind::Linear && g_lanes) {
      const auto r = static_cast<size_t>(group.region);
      const LaneWave wave{wave_modulus_[r], body_.sections[r].density, rest_speed_[r]};
      taken = linearFabricStableSteps(lane_laws_[r], wave, lane_elements_[static_cast<size_t>(g)],
                                      x, length_.data() + e0, lanes);
    }
    for (int k = 0; k < n; ++k)
      if (taken >> k & 1u)
        dt = std::min(dt, lanes[k]);
      else if (body_.sections[body_.mesh.region_of[e0 + k]].isLinear())
        dt = std::min(dt, elementStableStep(e0 + k, x, u));
  }
  return dt;
}

std::vector<CellField> LargeDeflection::cellFields(const Eigen::VectorXd& u) const {
  const int ne = body_.mesh.numElements();
  const auto sz = static_cast<size_t>(ne);
  CellField strain{"strain", 3, std::vector<double>(3 * sz)};
  CellField stress_f{"stress", 3, std::vector<double>(3 * sz)};
  CellField pstrain{"principal_strain", 2, std::vector<double>(2 * sz)};
  CellField pstress{"principal_stress", 2, std::vector<double>(2 * sz)};
  CellField wrinkled{"wrinkled", 1, std::vector<double>(sz)};
  CellField inelastic{"inelastic_strain", 1, std::vector<double>(sz, 0.0)};
  CellField inelastic_rate{"inelastic_strain_rate", 1, std::vector<double>(sz, 0.0)};
  CellField lambda3{"thickness_stretch", 1, std::vector<double>(sz, 1.0)};
#pragma omp parallel for schedule(static) if (ne > kParallelElements)
  for (int e = 0; e < ne; ++e) {
    const FabricStress st = stress(e, u);
    const auto k = static_cast<size_t>(e);
    const Eigen::Vector2d pe = principal2(st.E[0], st.E[1], 0.5 * st.E[2]);
    const Eigen::Vector2d ps = cauchyPrincipal(e, st);
    for (int c = 0; c < 3; ++c) {
      strain.values[3 * k + c] = st.E[c];
      stress_f.values[3 * k + c] = st.S[c];
    }
    for (int c = 0; c < 2; ++c) {
      pstrain.values[2 * k + c] = pe[c];
      pstress.values[2 * k + c] = ps[c];
    }
    wrinkled.values[k] = static_cast<double>(static_cast<int>(st.state));
    if (const double* b = history(e)) {
      inelastic.values[k] = b[LawPoint::kInelastic];
      inelastic_rate.values[k] = b[LawPoint::kInelasticRate];
      lambda3.values[k] = b[LawPoint::kLambda3];
    }
  }
  if (hasHistory())
    return {strain, stress_f, pstrain, pstress, wrinkled, inelastic, inelastic_rate, lambda3};
  return {strain, stress_f, pstrain, pstress, wrinkled};
}

void LargeDeflection::checkFailure(double t, const Eigen::VectorXd& u,
                                   FailureRecord& record) const {
  if (!any_threshold_)
    return;
  const int ne = body_.mesh.numElements();
  if (record.time.empty()) {
    record.time.assign(ne, -1.0);
    record.criterion.assign(ne, FailureCriterion::None);
  }
  std::vector<FailureCriterion> hit(ne, FailureCriterion::None);
#pragma omp parallel for schedule(static) if (ne > kParallelElements)
  for (int e = 0; e < ne; ++e) {
    if (record.time[e] >= 0)
      continue;
    const Section& s = body_.sections[body_.mesh.region_of[e]];
    if (!std::isfinite(s.failure_strain) && !std::isfinite(s.failure_stress))
      continue;
    const FabricStress st = stress(e, u);
    if (principal2(st.E[0], st.E[1], 0.5 * st.E[2])[0] >= s.failure_strain)
      hit[e] = FailureCriterion::Strain;
    else if (cauchyPrincipal(e, st)[0] >= s.failure_stress)
      hit[e] = FailureCriterion::Stress;
  }
  for (int e = 0; e < ne; ++e)
    if (hit[e] != FailureCriterion::None)
      record.mark(e, t, hit[e]);
}

} // namespace lamina::membrane
