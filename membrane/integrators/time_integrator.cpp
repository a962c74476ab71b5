#include "membrane/integrators/time_integrator.hpp"

#include "core/error.hpp"
#include "core/format.hpp"

#include <cmath>
#include <sstream>

namespace lamina::membrane {

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
