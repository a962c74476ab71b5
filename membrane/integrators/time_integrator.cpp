#include "membrane/integrators/time_integrator.hpp"

#include "core/error.hpp"

#include <cmath>
#include <sstream>

namespace lamina::membrane {

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
  os << "non-finite state at t = " << t1 << " s (step " << s.step + 1 << "), node " << bad
     << " at (" << p.x() << ", " << p.y() << ")" << hint;
  throw DivergenceError(os.str());
}

} // namespace lamina::membrane
