#include "membrane/integrators/time_integrator.hpp"

#include "core/error.hpp"
#include "core/format.hpp"

#include <cmath>
#include <sstream>

namespace lamina::membrane {

namespace {
/// The members of StateForces with their History names.
template <class F, class Fn>
void forEachForce(F& f, Fn&& fn) {
  fn("external", f.external);
  fn("drag", f.drag);
  fn("reaction", f.reaction);
  fn("spring", f.spring);
  fn("damping", f.damping);
  fn("internal", f.internal);
  fn("contact", f.contact.force);
  fn("contact_sum", f.contact.sum);
  fn("contact_depth", f.contact.depth);
}
} // namespace

void saveForces(const std::string& prefix, const StateForces& f, History& h) {
  forEachForce(f, [&](const char* name, const Eigen::VectorXd& v) {
    if (v.size())
      h[prefix + name] = v;
  });
}

void restoreForces(const std::string& prefix, const History& h, StateForces& f) {
  forEachForce(f, [&](const char* name, Eigen::VectorXd& v) {
    const std::string key = prefix + name;
    if (v.size() == 0 && h.count(key))
      throw Error("checkpoint has an entry '" + key + "' this run does not have");
    if (v.size())
      v = historyEntry(h, key, v.size());
  });
}

void TimeIntegrator::setTimeStep(double dt, const State& s) {
  (void)dt;
  (void)s;
  throw Error("the " + name() + " scheme has a fixed time step");
}

void commitStep(State& s, double t1, Eigen::VectorXd& u1, Eigen::VectorXd& v1,
                Eigen::VectorXd& a1) {
  std::swap(s.u, u1);
  std::swap(s.v, v1);
  std::swap(s.a, a1);
  s.t = t1;
  ++s.step;
}

void throwNonFinite(const Mesh& mesh, const State& s, double t1, const Eigen::VectorXd& u1,
                    const Eigen::VectorXd& v1, const Eigen::VectorXd& a1, const std::string& hint) {
  int bad = 0;
  for (Eigen::Index i = 0; i < u1.size(); ++i)
    if (!std::isfinite(u1[i]) || !std::isfinite(v1[i]) || !std::isfinite(a1[i])) {
      bad = static_cast<int>(i / 3);
      break;
    }
  const auto& p = mesh.nodes[bad];
  std::ostringstream os;
  os << "non-finite state at t = " << t1 << " s (step " << s.step + 1 << "), node "
     << mesh.nodeLabel(bad) << " at (" << p.x() << ", " << p.y() << ")" << hint;
  throw DivergenceError(os.str());
}

} // namespace lamina::membrane
