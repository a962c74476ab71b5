#pragma once
/// @file time_integrator.hpp
/// @brief The seam between a membrane model and a time-stepping scheme, in
/// the spirit of MFEM's SecondOrderODESolver: a scheme advances the state of
/// a SecondOrderSystem (system/second_order_system.hpp)
///   M a + f_int(u) = F(t, u, v) + R,
/// which gives it the forces at a state, the reactions R at the constrained
/// DOFs (whose velocities are prescribed) and the works; a scheme only
/// steps it and never knows which loads a case has.
///
/// Meaning of the state on entry and exit:
/// - init(s): on entry s.t, s.step, s.u and s.v hold the initial state (the
///   prescribed velocities already set); on exit s.a is the acceleration of
///   the equation of motion at s.t (zero at constrained DOFs whose velocity
///   is constant) and forces() holds the forces at s.
/// - step(s): on entry s is the state at t_n = timeAt(s.step) (as left by
///   init or by the previous step); on exit s is the state at
///   t_{n+1} = timeAt(s.step + 1) with s.step incremented, forces() holds the
///   forces at t_{n+1}, previousForces() those at t_n, increment() is
///   u_{n+1} - u_n. Times are step * dt (no accumulated round-off); a scheme
///   whose step changed (setTimeStep) counts from the state of the change. On a
///   non-finite result s is left unchanged and lamina::DivergenceError is
///   thrown naming the time and the node.
/// The works of the forces and the energy balance are kept outside the
/// schemes (SecondOrderSystem::addWorks, system/energy.hpp), from increment() and the forces at
/// both ends.
///
/// Checkpoints: saveHistory() puts into a History everything step() reads
/// besides the State (forces at t_n, past accelerations, solver history);
/// restoreHistory() on a scheme freshly set up and init()-ed on the same
/// model puts it back, after which step() continues bit for bit as the
/// scheme that saved it would have.

#include "membrane/model/mesh.hpp"
#include "membrane/system/state.hpp"

#include <Eigen/Dense>

#include <map>
#include <string>

namespace lamina::membrane {

/// Linear-solver statistics of a scheme (zero for explicit schemes).
struct SolverStats {
  long solves = 0;         ///< linear solves so far
  long iterations = 0;     ///< iterations summed over them
  int last_iterations = 0; ///< iterations of the last step
};

/// A time-stepping scheme (see the file comment for the contract).
class TimeIntegrator {
public:
  virtual ~TimeIntegrator() = default;
  /// Completes the initial state @p s (its acceleration) and the forces at it.
  virtual void init(State& s) = 0;
  /// Advances @p s by one step of timeStep().
  virtual void step(State& s) = 0;
  /// @return the step of the scheme (s): the one the next step() takes
  virtual double timeStep() const = 0;
  /// @return the time of step number @p step (s): step * timeStep() for a
  /// scheme whose step never changed (no accumulated round-off)
  virtual double timeAt(long step) const { return static_cast<double>(step) * timeStep(); }
  /// Changes the step from the state @p s on (times after it are s.t + k dt).
  /// Throws lamina::Error for a scheme with a fixed step.
  virtual void setTimeStep(double dt, const State& s);
  /// @return the forces at the current state
  virtual const StateForces& forces() const = 0;
  /// @return the forces at the start of the last step
  virtual const StateForces& previousForces() const = 0;
  /// @return u_{n+1} - u_n of the last step
  virtual const Eigen::VectorXd& increment() const = 0;
  /// @return the scheme's name for the summary ("newmark", ...)
  virtual std::string name() const = 0;
  /// @return linear-solver statistics
  virtual SolverStats stats() const { return {}; }
  /// @return seconds spent setting the scheme up (matrices, factorizations)
  virtual double setupSeconds() const { return 0; }
  /// Saves into @p h what step() depends on besides the State (keys of the
  /// scheme's own choosing, see the file comment).
  virtual void saveHistory(History& h) const = 0;
  /// Restores what saveHistory() wrote; call after init(). Throws
  /// lamina::Error naming a missing or mis-sized entry.
  virtual void restoreHistory(const History& h) = 0;
};

/// Commits a finite step of both schemes: @p s takes @p u1, @p v1, @p a1
/// by swaps (on return they hold u_n, v_n, a_n), s.t = @p t1 and s.step + 1.
void commitStep(State& s, double t1, Eigen::VectorXd& u1, Eigen::VectorXd& v1, Eigen::VectorXd& a1);

/// Throws lamina::DivergenceError for a step from @p s to time @p t1 whose
/// result @p u1, @p v1, @p a1 is not finite, naming the time, the step and
/// the first node with a non-finite value; @p hint is appended when not empty.
[[noreturn]] void throwNonFinite(const Mesh& mesh, const State& s, double t1,
                                 const Eigen::VectorXd& u1, const Eigen::VectorXd& v1,
                                 const Eigen::VectorXd& a1, const std::string& hint = "");

} // namespace lamina::membrane
