#include "membrane/simulation.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "membrane/integrators/central_difference.hpp"
#include "membrane/integrators/newmark.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lamina::membrane {

namespace {
/// The explicit step: time.dt when given (at most the stable step), else safety x stable.
double explicitStep(const TimeSettings& ts, double stable) {
  if (ts.dt > 0) {
    if (ts.dt > stable)
      throw Error("time.dt = " + core::formatShort(ts.dt) + " s exceeds the stable step " +
                  core::formatShort(stable) +
                  " s of the explicit integrator (leave dt out for safety x stable step)");
    return ts.dt;
  }
  return ts.safety * stable;
}
} // namespace

Simulation::Simulation(const Model& model)
    : model_(model), system_(model), structure_(system_.structure()) {
  stable_dt_ = rest_dt_ = system_.stableStep();
  if (model.time.integrator == IntegratorKind::Explicit)
    integrator_ =
        std::make_unique<CentralDifference>(system_, explicitStep(model.time, stable_dt_));
  else
    integrator_ = std::make_unique<Newmark>(system_);
  system_.setStep(integrator_->timeStep()); // each step receives its interval's impulse
  const int ndof = model.numDofs();
  state_.u = model.u0.size() == ndof ? model.u0 : Eigen::VectorXd::Zero(ndof);
  state_.v = model.v0.size() == ndof ? model.v0 : Eigen::VectorXd::Zero(ndof);
  system_.constraints().prescribe(0.0, state_.v);
  if (!model.contact.empty()) {
    state_.surfaces = initialMotion(model.contact);
    penetration_.resize(model.contact.size());
  }
  structure_.beginStep(0.0, 0.0); // a law meets the initial displacements instantaneously
  integrator_->init(state_);
  structure_.commitStep();
  u0_ = structure_.strainEnergy(state_.u);
  const Energy e = energy();
  e0_ = e.kinetic + e.strain;
  structure_.checkFailure(state_.t, state_.u, failure_);
  checkPenetration();
}

Simulation::~Simulation() = default;

void Simulation::checkPenetration() {
  const Eigen::VectorXd& depth = integrator_->forces().contact.depth;
  for (size_t k = 0; k < penetration_.size(); ++k) {
    const double d = depth[static_cast<Eigen::Index>(2 * k)];
    if (!(d > penetration_[k].depth))
      continue;
    const int node = static_cast<int>(depth[static_cast<Eigen::Index>(2 * k + 1)]);
    penetration_[k] = {d, state_.t, node};
    const ContactSurface& s = model_.contact[k];
    if (d > s.tolerance)
      throw DivergenceError(
          "rigid_surface '" + s.name + "': node " + std::to_string(model_.mesh.nodeLabel(node)) +
          " is " + core::formatShort(d) + " m inside it at t = " + core::formatShort(state_.t) +
          " s (step " + std::to_string(state_.step) + "), beyond its penetration_tolerance " +
          core::formatShort(s.tolerance) + " m: raise its penalty (or the tolerance)");
  }
}

void Simulation::step() {
  structure_.beginStep(integrator_->timeAt(state_.step + 1), integrator_->timeStep());
  integrator_->step(state_);
  structure_.commitStep();
  system_.addWorks(works_, integrator_->increment(), integrator_->previousForces(),
                   integrator_->forces());
  if (structure_.hasFailureThresholds())
    structure_.checkFailure(state_.t, state_.u, failure_);
  if (structure_.stateDependentStep() && state_.step % kStableStepEvery == 0)
    adaptStep();
  checkPenetration();
}

void Simulation::adaptStep() {
  if (model_.time.integrator != IntegratorKind::Explicit)
    return;
  stable_dt_ = system_.currentStableStep(state_.u);
  double target = model_.time.safety * stable_dt_;
  // A given step is the largest the run takes; one above safety x the rest
  // step (allowed up to the rest step) shrinks in proportion to the stable step.
  if (model_.time.dt > 0)
    target = std::min(model_.time.dt, std::max(target, model_.time.dt * (stable_dt_ / rest_dt_)));
  const double dt = integrator_->timeStep();
  // Shrink at once; grow back only by a margin, so that the step does not flutter.
  if (target < dt || target > kStepGrowth * dt) {
    integrator_->setTimeStep(target, state_);
    system_.setStep(target);
  }
}

namespace {
constexpr const char* kIntegrator = "integrator/";

/// A fingerprint of @p mesh's node and element order (the user's numbers in
/// the run's order; FNV-1a), below 2^52 so that a double holds it exactly.
double orderFingerprint(const Mesh& mesh) {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](std::uint64_t v) {
    h ^= v;
    h *= 1099511628211ULL;
  };
  for (int i = 0; i < mesh.numNodes(); ++i)
    mix(mesh.nodeLabel(i));
  for (int e = 0; e < mesh.numElements(); ++e)
    mix(mesh.elementLabel(e));
  return static_cast<double>(h >> 12);
}
} // namespace

void Simulation::save(History& h) const {
  h["state/time"] = Eigen::Vector2d(state_.t, static_cast<double>(state_.step));
  h["state/u"] = state_.u;
  h["mesh/order"] = Eigen::VectorXd::Constant(1, orderFingerprint(model_.mesh));
  h["state/v"] = state_.v;
  h["state/a"] = state_.a;
  h["works"] = (Eigen::VectorXd(6) << works_.external, works_.reaction, works_.drag, works_.spring,
                works_.damping, works_.internal)
                   .finished();
  if (!failure_.time.empty()) {
    const auto ne = static_cast<Eigen::Index>(failure_.time.size());
    h["failure/time"] = Eigen::Map<const Eigen::VectorXd>(failure_.time.data(), ne);
    Eigen::VectorXd c(ne);
    for (Eigen::Index e = 0; e < ne; ++e)
      c[e] = static_cast<double>(failure_.criterion[static_cast<size_t>(e)]);
    h["failure/criterion"] = c;
  }
  h["failure/first"] = Eigen::Vector3d(failure_.first_element, failure_.first_time,
                                       static_cast<double>(failure_.first_criterion));
  h["integrator/dt"] = Eigen::VectorXd::Constant(1, integrator_->timeStep());
  History own;
  integrator_->saveHistory(own);
  for (auto& [key, value] : own)
    h[kIntegrator + key] = std::move(value);
  structure_.saveHistory(h);
  if (structure_.stateDependentStep()) // the adapted stable step (the summary reports it)
    h["structure/stable_dt"] = Eigen::VectorXd::Constant(1, stable_dt_);
  if (!model_.contact.empty()) {
    const SurfaceMotion& m = state_.surfaces;
    h["state/surfaces"] = (Eigen::VectorXd(3 * m.u.size()) << m.u, m.v, m.a).finished();
    h["contact/work"] = Eigen::VectorXd::Constant(1, works_.contact);
    Eigen::VectorXd p(3 * static_cast<Eigen::Index>(penetration_.size()));
    for (size_t k = 0; k < penetration_.size(); ++k)
      p.segment<3>(3 * static_cast<Eigen::Index>(k)) =
          Eigen::Vector3d(penetration_[k].depth, penetration_[k].time, penetration_[k].node);
    h["contact/penetration"] = p;
  }
}

namespace {
/// A failure criterion stored as a double: one of FailureCriterion's values.
FailureCriterion criterionAt(const History& h, const std::string& key, Eigen::Index size,
                             Eigen::Index i) {
  return static_cast<FailureCriterion>(historyInteger(h, key, size, i, 0, 2));
}

/// Throws naming @p key unless @p t is -1 (no failure) or in [0, @p now].
void checkFailureTime(const std::string& key, double t, double now) {
  if (!(t == -1 || (t >= 0 && t <= now)))
    throw Error("checkpoint entry '" + key + "' holds the failure time " + core::formatShort(t) +
                " s, neither -1 (none) nor in [0, " + core::formatShort(now) + "] s");
}
} // namespace

void Simulation::restoreFailure(const History& h) {
  failure_ = FailureRecord{};
  const auto ne = model_.mesh.numElements();
  if (h.count("failure/time")) {
    const Eigen::VectorXd& t = historyEntry(h, "failure/time", ne);
    for (Eigen::Index e = 0; e < ne; ++e) {
      checkFailureTime("failure/time", t[e], state_.t);
      const FailureCriterion c = criterionAt(h, "failure/criterion", ne, e);
      if ((t[e] < 0) != (c == FailureCriterion::None))
        throw Error("checkpoint entries 'failure/time' and 'failure/criterion' disagree on "
                    "element " +
                    std::to_string(e));
      failure_.criterion.push_back(c);
    }
    failure_.time.assign(t.data(), t.data() + ne);
  } else if (h.count("failure/criterion")) {
    throw Error("checkpoint has an entry 'failure/criterion' without 'failure/time'");
  }
  failure_.first_element = static_cast<int>(historyInteger(h, "failure/first", 3, 0, -1, ne - 1));
  failure_.first_time = historyEntry(h, "failure/first", 3)[1];
  checkFailureTime("failure/first", failure_.first_time, state_.t);
  failure_.first_criterion = criterionAt(h, "failure/first", 3, 2);
  if ((failure_.first_element < 0) != (failure_.first_criterion == FailureCriterion::None))
    throw Error("checkpoint entry 'failure/first' names an element without a criterion or a "
                "criterion without an element");
}

void Simulation::restore(const History& h, long last_step) {
  // Every per-node and per-element entry is in the run's order: a checkpoint
  // of another order (an older build, another mesh.renumber) does not fit.
  if (!h.count("mesh/order") ||
      historyEntry(h, "mesh/order", 1)[0] != orderFingerprint(model_.mesh))
    throw Error("checkpoint entry 'mesh/order': written with another order of the mesh's nodes "
                "and elements (an older build of the program, or another mesh.renumber), its "
                "state does not fit this run; run the case again without --restart");
  const double dt = historyEntry(h, "integrator/dt", 1)[0];
  // An explicit run whose step adapts to the state may have changed it.
  const bool adaptive =
      model_.time.integrator == IntegratorKind::Explicit && structure_.stateDependentStep();
  if (dt != integrator_->timeStep() && !adaptive)
    throw Error("checkpoint was written with the time step " + core::formatExact(dt) +
                " s, this run's is " + core::formatExact(integrator_->timeStep()) +
                " s (another case or another build of the program)");
  restoreIntegrator(h);
  if (dt != integrator_->timeStep())
    throw Error("checkpoint entries 'integrator/dt' and 'integrator/step' disagree");
  system_.setStep(dt);
  const Eigen::Index n = model_.numDofs();
  state_.step = historyInteger(h, "state/time", 2, 1, 0, last_step);
  state_.t = historyEntry(h, "state/time", 2)[0];
  // The schemes compute t_n from the step count (no accumulated round-off): exactly.
  if (state_.t != integrator_->timeAt(state_.step))
    throw Error("checkpoint entry 'state/time' holds t = " + core::formatExact(state_.t) +
                " s at step " + std::to_string(state_.step) +
                ", not step * dt = " + core::formatExact(integrator_->timeAt(state_.step)) +
                " s (the scheme's time of that step)");
  state_.u = historyEntry(h, "state/u", n);
  state_.v = historyEntry(h, "state/v", n);
  state_.a = historyEntry(h, "state/a", n);
  const Eigen::VectorXd& w = historyEntry(h, "works", 6);
  works_ = Works{w[0], w[1], w[2], w[3], w[4], w[5]};
  restoreFailure(h);
  restoreContact(h);
  structure_.restoreHistory(h);
  if (structure_.stateDependentStep()) {
    if (!h.count("structure/stable_dt") && !structure_.hasHistory()) {
      // linear sections, written before their step followed the stretch
      stable_dt_ = system_.currentStableStep(state_.u);
    } else {
      stable_dt_ = historyEntry(h, "structure/stable_dt", 1)[0];
      if (!(stable_dt_ > 0))
        throw Error("checkpoint entry 'structure/stable_dt' must be > 0");
    }
  }
}

void Simulation::restoreContact(const History& h) {
  if (model_.contact.empty()) {
    for (const char* key : {"state/surfaces", "contact/work", "contact/penetration"})
      if (h.count(key))
        throw Error(std::string("checkpoint has an entry '") + key + "' this run does not have");
    return;
  }
  const auto ns = static_cast<Eigen::Index>(model_.contact.size());
  const Eigen::VectorXd& m = historyEntry(h, "state/surfaces", 9 * ns);
  state_.surfaces = {m.segment(0, 3 * ns), m.segment(3 * ns, 3 * ns), m.segment(6 * ns, 3 * ns)};
  works_.contact = historyEntry(h, "contact/work", 1)[0];
  const Eigen::VectorXd& p = historyEntry(h, "contact/penetration", 3 * ns);
  for (Eigen::Index k = 0; k < ns; ++k) {
    const double depth = p[3 * k], t = p[3 * k + 1];
    const auto node =
        historyInteger(h, "contact/penetration", 3 * ns, 3 * k + 2, -1, model_.mesh.numNodes() - 1);
    if (!(depth >= 0) || !(t >= 0 && t <= state_.t) || (node < 0) != (depth == 0))
      throw Error("checkpoint entry 'contact/penetration' holds the depth " +
                  core::formatShort(depth) + " m at t = " + core::formatShort(t) + " s, node " +
                  std::to_string(node) + " for rigid_surface '" +
                  model_.contact[static_cast<size_t>(k)].name + "'");
    penetration_[static_cast<size_t>(k)] = {depth, t, static_cast<int>(node)};
  }
}

void Simulation::restoreIntegrator(const History& h) {
  History own;
  const std::string prefix = kIntegrator;
  for (auto it = h.lower_bound(prefix); it != h.end() && it->first.rfind(prefix, 0) == 0; ++it)
    if (it->first != "integrator/dt")
      own[it->first.substr(prefix.size())] = it->second;
  try {
    integrator_->restoreHistory(own);
  } catch (const Error& e) { // name the entries as the file does: "integrator/<key>"
    std::string m = e.message();
    for (auto at = m.find("entry '"); at != std::string::npos; at = m.find("entry '", at + 1))
      m.insert(at + 7, prefix);
    throw Error(m, e.context());
  }
}

Energy Simulation::energy() const {
  Eigen::VectorXd y;
  multiply(structure_.mass(), state_.v, y);
  const double T = 0.5 * state_.v.dot(y);
  // U is the stored energy; without a potential (tension-only fabric) the
  // internal work it does not hold is the wrinkling dissipation.
  const double U = structure_.strainEnergy(state_.u);
  // A law's dissipation comes from its own history; the tension-only
  // projection of elastic sections dissipates (or makes) what the internal
  // work leaves over.
  const double D_in = structure_.inelasticDissipation();
  const double D_w =
      structure_.nonConservativeWrinkling() ? works_.internal - (U - u0_) - D_in : 0.0;
  Energy e = works_.energy(T, U, e0_, D_w, D_in);
  if (const SparseMatrix* MD = structure_.microMass()) {
    multiply(*MD, state_.v, y);
    e.micro_kinetic = 0.5 * state_.v.dot(y);
  }
  return e;
}

std::vector<Eigen::Vector3d> Simulation::reactionSums() const {
  return system_.reactionSums(integrator_->forces(), state_.u);
}

std::vector<std::string> Simulation::reactionNames() const {
  return system_.reactionNames();
}

Eigen::Vector3d Simulation::dragSum() const {
  return system_.dragSum(integrator_->forces());
}

const SparseMatrix& Simulation::K() const {
  LAMINA_CHECK(structure_.stiffness() != nullptr, "the model has no constant stiffness K");
  return *structure_.stiffness();
}

} // namespace lamina::membrane
