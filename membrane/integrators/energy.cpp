#include "membrane/integrators/energy.hpp"

namespace lamina::membrane {

void Works::add(const Eigen::VectorXd& du, const StateForces& f0, const StateForces& f1,
                const ConstrainedDofs& cons, bool has_external, bool has_drag) {
  if (has_external)
    external += 0.5 * du.dot(f0.external + f1.external);
  if (has_drag)
    drag += 0.5 * du.dot(f0.drag + f1.drag);
  if (f1.spring.size())
    spring += 0.5 * du.dot(f0.spring + f1.spring);
  if (f1.damping.size())
    damping += 0.5 * du.dot(f0.damping + f1.damping);
  if (f1.internal.size())
    internal += 0.5 * du.dot(f0.internal + f1.internal);
  for (size_t k = 0; k < cons.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    reaction += 0.5 * du[cons.dofs()[k]] * (f0.reaction[i] + f1.reaction[i]);
  }
}

Energy Works::energy(double T, double U, double e0, double D, double D_in) const {
  Energy e;
  e.kinetic = T;
  e.strain = U;
  e.external_work = external;
  e.reaction_work = reaction;
  e.drag_work = drag;
  e.spring_work = spring;
  e.damping_work = damping;
  e.wrinkling_dissipation = D;
  e.inelastic_dissipation = D_in;
  e.balance = T + U + D + D_in - e0 - external - reaction - drag - spring - damping;
  return e;
}

} // namespace lamina::membrane
