#include "homogenize/conjugate_gradients.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/interrupt.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace lamina::homogenize {

CgControl CgControl::relative(double tol, double scale, int max_iterations) {
  CgControl c;
  c.scale = scale;
  c.rz_stop = tol * tol * scale;
  c.tol = tol;
  c.max_iterations = max_iterations;
  return c;
}

CgControl CgControl::absolute(double stop, double scale, int max_iterations) {
  CgControl c;
  c.scale = scale;
  c.rz_stop = stop * stop;
  c.tol = stop / std::sqrt(scale);
  c.max_iterations = max_iterations;
  return c;
}

namespace {

double relativeResidual(double rz, const CgControl& c) {
  return std::sqrt(std::max(rz, 0.0) / c.scale);
}

[[noreturn]] void notConverged(const CgControl& c, double residual) {
  std::ostringstream os;
  os << "conjugate gradients did not reach tol " << c.tol << " in " << c.max_iterations
     << " iterations (residual " << residual << ")";
  throw Error(os.str());
}

} // namespace

CgResult conjugateGradients(CgProblem& problem, const CgControl& control,
                            const std::function<void(int, double)>& monitor) {
  double rz = problem.start();
  CgResult res;
  res.residual = relativeResidual(rz, control);
  while (rz > control.rz_stop) {
    // a safe point: under an InterruptGuard (the Python module's long
    // calls) Ctrl-C stops the solve here; without one this never throws
    core::throwIfInterrupted("homogenization");
    if (res.iterations >= control.max_iterations)
      notConverged(control, res.residual);
    const double pw = problem.applyToDirection();
    const double alpha = rz / pw;
    if (!(pw > 0) || !std::isfinite(pw) || !std::isfinite(alpha))
      throw DivergenceError("conjugate gradients broke down (p^T A p = " + core::formatShort(pw) +
                            "): NaN/Inf or " + problem.indefiniteCause());
    const double rz_new = problem.update(alpha, rz, control.rz_stop);
    if (!std::isfinite(rz_new))
      throw DivergenceError("residual is NaN/Inf in conjugate gradients");
    rz = rz_new;
    ++res.iterations;
    res.residual = relativeResidual(rz, control);
    if (monitor)
      monitor(res.iterations, res.residual);
  }
  return res;
}

} // namespace lamina::homogenize
