#include "membrane/system/energy.hpp"

#include "core/parallel.hpp"

#include <vector>

namespace lamina::membrane {

namespace {
/// @return du.(a + b) / 2: Eigen's dot on one thread (its summation order,
/// unchanged), on several the dots of the threads' static shares summed in
/// thread order (a serial pass over three vectors per work was a large part
/// of a fast step's time).
double halfWork(const Eigen::VectorXd& du, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const auto n = static_cast<int>(du.size());
  const int threads = omp_get_max_threads();
  if (n <= kParallelDofs || threads == 1)
    return 0.5 * du.dot(a + b);
  std::vector<double> part(static_cast<size_t>(threads), 0.0);
#pragma omp parallel num_threads(threads)
  {
    const auto [begin, end] = core::threadRange(n);
    const int len = end - begin;
    part[static_cast<size_t>(omp_get_thread_num())] =
        du.segment(begin, len).dot(a.segment(begin, len) + b.segment(begin, len));
  }
  double sum = 0;
  for (double p : part)
    sum += p;
  return 0.5 * sum;
}
} // namespace

void Works::add(const Eigen::VectorXd& du, const StateForces& f0, const StateForces& f1,
                const ConstrainedDofs& cons, bool has_external, bool has_drag) {
  if (has_external)
    external += halfWork(du, f0.external, f1.external);
  if (has_drag)
    drag += halfWork(du, f0.drag, f1.drag);
  if (f1.spring.size())
    spring += halfWork(du, f0.spring, f1.spring);
  if (f1.damping.size())
    damping += halfWork(du, f0.damping, f1.damping);
  if (f1.internal.size())
    internal += halfWork(du, f0.internal, f1.internal);
  if (f1.contact.force.size())
    contact += halfWork(du, f0.contact.force, f1.contact.force);
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
  e.contact_work = contact;
  e.wrinkling_dissipation = D;
  e.inelastic_dissipation = D_in;
  e.balance = T + U + D + D_in - e0 - external - reaction - drag - spring - damping - contact;
  return e;
}

} // namespace lamina::membrane
