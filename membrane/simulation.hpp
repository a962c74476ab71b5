#pragma once
/// @file simulation.hpp
/// @brief A running simulation of one Model (system/model.hpp): its
/// second-order system (system/second_order_system.hpp: the structure of
/// model/ and everything acting on it), a time integrator (integrators/)
/// stepping it, and the energy bookkeeping (system/energy.hpp).
///
/// The scheme and its equations are documented with each integrator
/// (integrators/newmark.hpp for the paper's scheme,
/// integrators/central_difference.hpp for the explicit one). The structure
/// is the model's kind (LinearMembrane or LargeDeflection); the explicit
/// step is time.dt when given (it must not exceed the stable step), else
/// time.safety x the structure's stable step. When a section's law carries
/// history (structure.hpp), the step follows the law's instantaneous
/// stiffness at the current state: every kStableStepEvery steps it becomes
/// time.safety x the current stable step (at most time.dt when given). The
/// stable step includes the springs' and the contact penalties' stiffness.

#include "membrane/integrators/time_integrator.hpp"
#include "membrane/system/energy.hpp"
#include "membrane/system/model.hpp"
#include "membrane/system/second_order_system.hpp"

#include <Eigen/Dense>

#include <memory>
#include <vector>

namespace lamina::membrane {

/// A running simulation of one Model.
class Simulation {
public:
  /// Builds the structure (assembles K and M), the integrator (for Newmark:
  /// A with the constraints and its solver) and the initial state
  /// (consistent initial acceleration).
  explicit Simulation(const Model& model);
  ~Simulation();

  /// Advances one step. On a non-finite state the step is not committed
  /// (the state stays the last finite one) and lamina::DivergenceError is
  /// thrown naming the time and the node.
  void step();

  /// @return current time (s)
  double time() const { return state_.t; }
  /// @return number of steps taken
  long steps() const { return state_.step; }
  /// @return displacements (3 per node)
  const Eigen::VectorXd& u() const { return state_.u; }
  /// @return velocities
  const Eigen::VectorXd& v() const { return state_.v; }
  /// @return accelerations
  const Eigen::VectorXd& a() const { return state_.a; }
  /// @return the whole state (t, step, u, v, a)
  const State& state() const { return state_; }
  /// @return the works accumulated so far
  const Works& works() const { return works_; }
  /// @return energies now (costs two SpMV)
  Energy energy() const;
  /// @return energy at t = 0 (T + U)
  double initialEnergy() const { return e0_; }
  /// @return reaction force summed per constraint set, then per spring set
  /// (the springs' force on the structure), then per rigid surface (its
  /// contact force on the membrane) (N), current step
  std::vector<Eigen::Vector3d> reactionSums() const;
  /// @return the names of the reaction sets (constraints, springs, rigid surfaces)
  std::vector<std::string> reactionNames() const;
  /// @return per rigid surface, the deepest penetration so far
  const std::vector<PenetrationPeak>& penetration() const { return penetration_; }
  /// @return the stable step of explicit central differences (s, no safety factor)
  double stableStep() const { return stable_dt_; }
  /// @return the failure record (empty time list without thresholds)
  const FailureRecord& failure() const { return failure_; }
  /// @return drag force summed over all nodes (N), current step
  Eigen::Vector3d dragSum() const;
  /// @return global stiffness (linear model only; throws otherwise)
  const SparseMatrix& K() const;
  /// @return global mass (with point masses)
  const SparseMatrix& M() const { return system_.mass(); }
  /// @return seconds spent assembling K and M
  double assemblySeconds() const { return system_.structure().setupSeconds(); }
  /// @return seconds spent setting up the integrator (A and its solver)
  double setupSeconds() const { return integrator_->setupSeconds(); }
  /// @return iterations of the last solve (sum over drag iterations)
  int lastIterations() const { return integrator_->stats().last_iterations; }
  /// @return the time integrator
  const TimeIntegrator& integrator() const { return *integrator_; }
  /// @return the structure
  const Structure& structure() const { return system_.structure(); }
  /// @return the second-order system the integrator steps
  const SecondOrderSystem& system() const { return system_; }
  /// @return the model
  const Model& model() const { return model_; }

  /// Saves into @p h everything the next step depends on: the State
  /// ("state/..."), the works ("works"), the failure record ("failure/..."),
  /// the scheme's step ("integrator/dt") and its history ("integrator/...").
  /// The loads hold no state (they are functions of t, u and v).
  void save(History& h) const;
  /// Restores what save() wrote, on a simulation just built from the same
  /// model; the next step() then continues bit for bit. A checkpoint is
  /// input: throws lamina::Error naming the entry when one is missing or
  /// mis-sized, when the step count is not an integer in [0, @p last_step]
  /// or the time not step * dt, when a failure record names no element, no
  /// criterion or a time after the state's, or when the scheme's step
  /// differs from the saved one (another case or another build).
  void restore(const History& h, long last_step);

  /// Steps between two re-evaluations of the stable step of a structure whose
  /// laws carry history (the step follows their instantaneous stiffness).
  static constexpr long kStableStepEvery = 10;
  /// The step grows back only when the stable one exceeds it by this factor.
  static constexpr double kStepGrowth = 1.2;

private:
  /// The explicit step from the structure's current stable step: safety x
  /// it (at most time.dt when given), shrunk at once, grown by kStepGrowth.
  void adaptStep();
  /// restore()'s part of the integrator: its own entries "integrator/<key>".
  void restoreIntegrator(const History& h);
  /// restore()'s failure record: element indices, criteria and times checked.
  void restoreFailure(const History& h);
  /// Updates the deepest penetration per rigid surface from the current
  /// forces; throws lamina::DivergenceError naming the surface, node, time
  /// and depth when one exceeds its penetration_tolerance.
  void checkPenetration();
  /// restore()'s contact entries: the surfaces' motion, the contact work
  /// and the deepest penetrations.
  void restoreContact(const History& h);
  const Model& model_;
  SecondOrderSystem system_;
  Structure& structure_; // system_'s, whose history the run steps
  std::unique_ptr<TimeIntegrator> integrator_;
  State state_;
  Works works_;
  FailureRecord failure_;
  std::vector<PenetrationPeak> penetration_; // per rigid surface
  double e0_ = 0, u0_ = 0, stable_dt_ = 0;
  double rest_dt_ = 0; // the stable step of the initial state
};

} // namespace lamina::membrane
