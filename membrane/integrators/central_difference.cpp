#include "membrane/integrators/central_difference.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace lamina::membrane {

CentralDifference::CentralDifference(const SecondOrderSystem& system, double dt)
    : system_(system), cons_(system.constraints()), dt_(dt) {
  LAMINA_CHECK(dt > 0 && std::isfinite(dt), "explicit time step must be > 0");
  // Row sums of the gradient inertia M_D are zero (B of a translation is 0):
  // lumping would drop micro-inertia silently
  if (system.structure().microMass())
    throw Error("micro-inertia (a section with a dispersion zeta^2 D) needs the Newmark "
                "scheme: its gradient mass cannot be lumped; use time.integrator = \"newmark\" "
                "or micro_inertia = false in the section");
  const int ndof = system.numDofs();
  // Lumped mass: row sums (the diagonal itself for a lumped model).
  const Eigen::VectorXd& m = system.lumpedMass();
  minv_ = Eigen::VectorXd::Zero(ndof);
  for (int i = 0; i < ndof; ++i) {
    LAMINA_CHECK(m[i] > 0, "explicit integration: DOF ", i, " (node ",
                 system.model().mesh.nodeLabel(i / 3), ") has no mass");
    minv_[i] = cons_.mask()[i] ? 0.0 : 1.0 / m[i];
  }
  by_dof_.resize(cons_.size());
  for (size_t k = 0; k < cons_.size(); ++k)
    by_dof_[k] = static_cast<int>(k);
  std::stable_sort(by_dof_.begin(), by_dof_.end(),
                   [&](int p, int q) { return cons_.dofs()[p] < cons_.dofs()[q]; });
  for (const int k : by_dof_)
    sorted_dof_.push_back(cons_.dofs()[k]);
  for (const auto& r : system.rigidSets()) {
    double mass = 0;
    for (int d : r.dofs)
      mass += m[d];
    rigid_mass_.push_back(mass);
  }
}

namespace {
/// The force of a = m^-1 (F_ext + F_drag + F_s + F_damp + F_c - f_int), DOF
/// by DOF; absent terms are null (a zero external force or drag adds +0 exactly).
struct ForceTotal {
  const double *ext, *drag, *fi, *spring, *damp, *contact;
  ForceTotal(const StateForces& f, bool external, bool drag_force)
      : ext(external ? f.external.data() : nullptr), drag(drag_force ? f.drag.data() : nullptr),
        fi(f.internal.data()), spring(f.spring.size() ? f.spring.data() : nullptr),
        damp(f.damping.size() ? f.damping.data() : nullptr),
        contact(f.contact.force.size() ? f.contact.force.data() : nullptr) {}
  double operator()(int i) const {
    // The sum ext + drag - fi of every step, with +0 for an absent term.
    double t = ((ext ? ext[i] : 0.0) + (drag ? drag[i] : 0.0)) - fi[i];
    if (spring)
      t += spring[i];
    if (damp)
      t += damp[i];
    if (contact)
      t += contact[i];
    return t;
  }
};

/// The drift on the DOFs [@p i0, @p i1) in lanes: vh = v + h a, u1 = u + dt vh,
/// du = u1 - u. @return how many u1 there are not finite (constrained DOFs
/// included: the caller corrects their count when it sets them).
LAMINA_VECTOR_CLONES int driftLanes(const double* __restrict u, const double* __restrict v,
                                    const double* __restrict a, double h, double dt,
                                    double* __restrict vh, double* __restrict u1,
                                    double* __restrict du, int i0, int i1) {
  core::LaneMask bad = 0;
#pragma omp simd reduction(+ : bad)
  for (int i = i0; i < i1; ++i) {
    const double w = v[i] + h * a[i];
    const double x = u[i] + dt * w;
    vh[i] = w;
    u1[i] = x;
    du[i] = x - u[i];
    bad += 1 - core::finiteLane(x);
  }
  return static_cast<int>(bad);
}

/// The kick on the DOFs [@p i0, @p i1) in lanes when the only forces are the
/// external force (@p Ext), the drag (@p Drag) and the internal force:
/// a1 = minv ((ext + drag) - fi) (+0 for an absent term, as ForceTotal),
/// v1 = vh + h a1. @return how many DOFs there have a1 or v1 not finite
/// (constrained DOFs included: the caller corrects them).
template <bool Ext, bool Drag>
LAMINA_VECTOR_CLONES int kickLanes(const double* __restrict ext, const double* __restrict drag,
                                   const double* __restrict fi, const double* __restrict minv,
                                   const double* __restrict vh, double h, double* __restrict a1,
                                   double* __restrict v1, int i0, int i1) {
  core::LaneMask bad = 0;
#pragma omp simd reduction(+ : bad)
  for (int i = i0; i < i1; ++i) {
    const double t = ((Ext ? ext[i] : 0.0) + (Drag ? drag[i] : 0.0)) - fi[i];
    const double acc = minv[i] * t;
    const double vel = vh[i] + h * acc;
    a1[i] = acc;
    v1[i] = vel;
    bad += 1 - core::finiteLane(acc) * core::finiteLane(vel);
  }
  return static_cast<int>(bad);
}

/// A rigid set's DOFs take its total force over its total mass @p mass.
void accelerateRigid(const std::vector<RigidSet>& rigid, const std::vector<double>& mass,
                     const ForceTotal& total, double* a) {
  for (size_t k = 0; k < rigid.size(); ++k) {
    double sum = 0;
    for (int d : rigid[k].dofs)
      sum += total(d);
    for (int d : rigid[k].dofs)
      a[d] = sum / mass[k];
  }
}
} // namespace

void CentralDifference::accelerate(const StateForces& f, Eigen::VectorXd& a) const {
  // a = m^-1 (F_ext + F_drag + F_s + F_damp - f_int) in one threaded pass.
  const int n = system_.numDofs();
  a.resize(n);
  const ForceTotal total(f, true, true);
  const double* minv = minv_.data();
  double* ap = a.data();
#pragma omp parallel for schedule(static) if (n > kParallelDofs)
  for (int i = 0; i < n; ++i)
    ap[i] = minv[i] * total(i);
  accelerateRigid(system_.rigidSets(), rigid_mass_, total, ap);
}

void CentralDifference::reactions(const Eigen::VectorXd& a, StateForces& f) {
  // m a + f_int at the constrained DOFs; the system subtracts the forces.
  inertia_.resize(static_cast<Eigen::Index>(cons_.size()));
  const Eigen::VectorXd& m = system_.lumpedMass();
  for (size_t k = 0; k < cons_.size(); ++k) {
    const int d = cons_.dofs()[k];
    inertia_[static_cast<Eigen::Index>(k)] = m[d] * a[d] + f.internal[d];
  }
  system_.reactions(inertia_, f);
}

void CentralDifference::init(State& s) {
  system_.forces(s.t, s.u, s.v, s.surfaces.u, s.surfaces.v, cur_);
  accelerate(cur_, s.a);
  if (system_.hasContact())
    setAccelerations(system_.model().contact, cur_.contact.sum, s.surfaces.a);
  for (int d : cons_.dofs())
    s.a[d] = 0;
  reactions(s.a, cur_);
  prev_ = cur_;
  du_ = Eigen::VectorXd::Zero(system_.numDofs());
}

void CentralDifference::setTimeStep(double dt, const State& s) {
  LAMINA_CHECK(dt > 0 && std::isfinite(dt), "explicit time step must be > 0");
  dt_ = dt;
  t_base_ = s.t;
  step_base_ = s.step;
}

void CentralDifference::saveHistory(History& h) const {
  saveForces("forces/", cur_, h);
  h["step"] = Eigen::Vector3d(dt_, t_base_, static_cast<double>(step_base_));
}

void CentralDifference::restoreHistory(const History& h) {
  restoreForces("forces/", h, cur_); // every force of init(), with its size
  prev_ = cur_;
  const Eigen::VectorXd& st = historyEntry(h, "step", 3);
  if (!(st[0] > 0 && std::isfinite(st[0])) || !(st[1] >= 0 && std::isfinite(st[1])))
    throw Error("checkpoint entry 'step' holds the step " + std::to_string(st[0]) +
                " s from t = " + std::to_string(st[1]) + " s (need a step > 0 from t >= 0)");
  dt_ = st[0];
  t_base_ = st[1];
  step_base_ = historyInteger(h, "step", 3, 2, 0, std::numeric_limits<long>::max() / 2);
}

std::pair<int, int> CentralDifference::constrainedIn(int i0, int i1) const {
  const auto first = std::lower_bound(sorted_dof_.begin(), sorted_dof_.end(), i0);
  const auto last = std::lower_bound(first, sorted_dof_.end(), i1);
  return {static_cast<int>(first - sorted_dof_.begin()),
          static_cast<int>(last - sorted_dof_.begin())};
}

bool CentralDifference::firstOf(int c, int c0) const {
  return c == c0 || sorted_dof_[c - 1] != sorted_dof_[c];
}

int CentralDifference::drift(const State& s, double th) {
  // v_{n+1/2} = v_n + dt/2 a_n, u_{n+1} and du; each thread then sets the
  // constrained DOFs of its share (their data are near in its cache).
  const int n = system_.numDofs();
  const double h = 0.5 * dt_, dt = dt_;
  vh_.resize(n);
  u1_.resize(n);
  du_.resize(n);
  int non_finite = 0;
  const double *u = s.u.data(), *v = s.v.data(), *a = s.a.data();
  double *vh = vh_.data(), *u1 = u1_.data(), *du = du_.data();
#pragma omp parallel reduction(+ : non_finite) if (n > kParallelDofs)
  {
    const auto [i0, i1] = core::threadRange(n);
    non_finite += driftLanes(u, v, a, h, dt, vh, u1, du, i0, i1);
    const auto [c0, c1] = constrainedIn(i0, i1);
    for (int c = c0; c < c1; ++c) {
      const int d = sorted_dof_[c];
      if (firstOf(c, c0)) // the lanes counted it as a free DOF
        non_finite -= !std::isfinite(u1[d]);
      vh[d] = cons_.velocity(static_cast<size_t>(by_dof_[c]), th);
      u1[d] = u[d] + dt * vh[d];
      du[d] = u1[d] - u[d];
      non_finite += !std::isfinite(u1[d]);
    }
  }
  return non_finite;
}

int CentralDifference::kick(const State& s, double t1, const StateForces& next) {
  // a_{n+1} = m^-1 F, v_{n+1} = v_{n+1/2} + dt/2 a_{n+1}; without rigid sets
  // each thread then sets the constrained DOFs of its share and their m a +
  // f_int (the reactions' inertia), else the rigid sets first, then those.
  const int n = system_.numDofs();
  const double h = 0.5 * dt_;
  a1_.resize(n);
  v1_.resize(n);
  inertia_.resize(static_cast<Eigen::Index>(cons_.size()));
  const bool in_shares = system_.rigidSets().empty();
  int non_finite = 0;
  const char* fixed = cons_.mask().data();
  const ForceTotal total(next, system_.hasExternal(), system_.hasDrag());
  const double *vh = vh_.data(), *minv = minv_.data(), *m = system_.lumpedMass().data();
  double *a1 = a1_.data(), *v1 = v1_.data();
  const auto bad = [&](int d) { return int(!std::isfinite(v1[d]) || !std::isfinite(a1[d])); };
  auto constrain = [&](int c) { // the constrained DOF at place c of sorted_dof_
    const int d = sorted_dof_[c], k = by_dof_[c];
    v1[d] = cons_.velocity(static_cast<size_t>(k), t1);
    a1[d] = (v1[d] - s.v[d]) / dt_;
    inertia_[k] = m[d] * a1[d] + next.internal[d];
    return bad(d);
  };
  // Lanes when the force is ext + drag - fi only, else ForceTotal DOF by DOF.
  const bool lanes = !total.spring && !total.damp && !total.contact;
  const auto lanesOf = [&](int i0, int i1) {
    const double* fi = next.internal.data();
    if (total.ext && total.drag)
      return kickLanes<true, true>(total.ext, total.drag, fi, minv, vh, h, a1, v1, i0, i1);
    if (total.ext)
      return kickLanes<true, false>(total.ext, nullptr, fi, minv, vh, h, a1, v1, i0, i1);
    if (total.drag)
      return kickLanes<false, true>(nullptr, total.drag, fi, minv, vh, h, a1, v1, i0, i1);
    return kickLanes<false, false>(nullptr, nullptr, fi, minv, vh, h, a1, v1, i0, i1);
  };
#pragma omp parallel reduction(+ : non_finite) if (n > kParallelDofs)
  {
    const auto [i0, i1] = core::threadRange(n);
    if (lanes) {
      non_finite += lanesOf(i0, i1);
    } else {
      for (int i = i0; i < i1; ++i) {
        a1[i] = minv[i] * total(i);
        v1[i] = vh[i] + h * a1[i];
        non_finite += !std::isfinite(v1[i]) || !std::isfinite(a1[i]);
      }
    }
    // The lanes counted the constrained DOFs of this share as free: take
    // their counts back before the rigid sets or the constraints set them.
    const auto [c0, c1] = constrainedIn(i0, i1);
    for (int c = c0; c < c1; ++c) {
      if (firstOf(c, c0))
        non_finite -= bad(sorted_dof_[c]);
      if (in_shares)
        non_finite += constrain(c);
    }
  }
  if (in_shares)
    return non_finite;
  accelerateRigid(system_.rigidSets(), rigid_mass_, total, a1);
  for (const RigidSet& r : system_.rigidSets())
    for (int d : r.dofs) {
      v1[d] = vh[d] + h * a1[d];
      non_finite += !fixed[d] && (!std::isfinite(v1[d]) || !std::isfinite(a1[d]));
    }
  for (int c = 0; c < static_cast<int>(sorted_dof_.size()); ++c)
    non_finite += constrain(c);
  return non_finite;
}

void CentralDifference::step(State& s) {
  // The vector work is two threaded passes around the force evaluation:
  // v_{n+1/2}, u_{n+1} and du, then a_{n+1} and v_{n+1}.
  const double t1 = timeAt(s.step + 1);
  const double th = t_base_ + (static_cast<double>(s.step - step_base_) + 0.5) * dt_;
  int non_finite = drift(s, th);
  if (system_.hasContact())
    predictMotion(system_.model().contact, s.surfaces, t1, dt_, surf1_.u, svh_);
  StateForces& next = prev_; // a_{n-1}'s forces are no longer needed
  system_.forces(t1, u1_, vh_, surf1_.u, svh_, next);
  non_finite += kick(s, t1, next);
  if (system_.hasContact())
    non_finite += finishSurfaces(next);
  if (non_finite > 0)
    throwNonFinite(system_.model().mesh, s, t1, u1_, v1_, a1_,
                   "; the explicit step may exceed the stable step");
  system_.reactions(inertia_, next); // m a + f_int at the constrained DOFs (kick)
  commitStep(s, t1, u1_, v1_, a1_);
  if (system_.hasContact())
    std::swap(s.surfaces, surf1_);
  std::swap(prev_, cur_);
}

int CentralDifference::finishSurfaces(const StateForces& f) {
  // Prescribed surfaces: a = 0 and v1 = vh = their velocity, exactly.
  setAccelerations(system_.model().contact, f.contact.sum, surf1_.a);
  surf1_.v = svh_ + (0.5 * dt_) * surf1_.a;
  int non_finite = 0;
  for (Eigen::Index i = 0; i < surf1_.v.size(); ++i)
    non_finite +=
        !std::isfinite(surf1_.u[i]) || !std::isfinite(surf1_.v[i]) || !std::isfinite(surf1_.a[i]);
  return non_finite;
}

} // namespace lamina::membrane
