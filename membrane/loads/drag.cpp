#include "membrane/loads/drag.hpp"

#include <cmath>

namespace lamina::membrane {

void addDragForce(const Drag& d, const Eigen::VectorXd& v, Eigen::VectorXd& f) {
  // Drag paper eqs. (1)-(3): F_i = 1/2 rho_f V_i^2 A_i C_d along the normal
  // (e_z of the flat membrane), opposite to the normal motion.
  for (size_t k = 0; k < d.nodes.size(); ++k) {
    const int i = d.nodes[k];
    const double vn = v[3 * i + 2];
    const double speed = d.resultant ? v.segment<3>(3 * i).norm() : std::abs(vn);
    // 'normal': V = |v_n|, F = -q V v_n; 'resultant': V = |v|, direction by sign(v_n).
    const double q = 0.5 * d.fluid_density * d.cd * d.area[k];
    f[3 * i + 2] -= d.resultant ? q * speed * speed *
                                      (vn > 0   ? 1.0
                                       : vn < 0 ? -1.0
                                                : 0.0)
                                : q * speed * vn;
  }
}

} // namespace lamina::membrane
