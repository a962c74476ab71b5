#pragma once
/// @file second_order_system.hpp
/// @brief The semi-discrete equation of motion of a Model, in the spirit of
/// MFEM's SecondOrderTimeDependentOperator:
///   M a + f_int(u) = F_ext(t, u) + F_drag(u, v) + F_s(u) + F_damp(v)
///                    + F_c(u, v, surfaces) + R
/// with M and f_int the structure's (model/structure.hpp: the paper's linear
/// membrane or the large-deflection fabric), F_ext the loads (fixed patterns,
/// pressures, blasts), F_drag the drag, F_s = -K_s u the springs to the
/// ground, F_damp = -c m v the mass-proportional damping (m the lumped
/// mass), F_c the rigid surfaces' contact, and R the reactions at the
/// constrained DOFs, whose velocities are prescribed. Rigid sets tie DOFs to
/// one acceleration.
///
/// The system owns the structure, the loads, the constraints, the springs,
/// the rigid sets and the contact; a time integrator (integrators/) only
/// steps it: it asks the system for the forces at a state, for the
/// reactions once it knows the inertia and the internal force there, and
/// hands the forces at both ends of a step to the works (energy.hpp). A
/// scheme never knows which loads a case has.
///
/// Forces are nodal force vectors of length 3 * nodes (N), the DOF numbering
/// of assembly.hpp. Time-dependent loads give their means over the interval
/// a force stands for in a step of the scheme (setStep()).

#include "membrane/model/constraint.hpp"
#include "membrane/model/structure.hpp"
#include "membrane/system/energy.hpp"
#include "membrane/system/model.hpp"
#include "membrane/system/state.hpp"

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

namespace lamina::membrane {

/// The second-order system of one Model (see the file comment).
class SecondOrderSystem {
public:
  /// Builds the structure of @p model (assembles M, and K for the linear
  /// model) and flattens its constraints. @p model must outlive the system.
  explicit SecondOrderSystem(const Model& model);
  ~SecondOrderSystem();

  /// @return the model
  const Model& model() const { return model_; }
  /// @return the structure (M, f_int), whose history the owner of the run steps
  Structure& structure() { return *structure_; }
  /// @return the structure
  const Structure& structure() const { return *structure_; }
  /// @return the constrained DOFs (the order of the reaction vectors)
  const ConstrainedDofs& constraints() const { return cons_; }
  /// @return the number of DOFs (3 per node)
  int numDofs() const { return structure_->numDofs(); }
  /// @return the mass matrix M (kg)
  const SparseMatrix& mass() const { return structure_->mass(); }
  /// @return the row sums of M: the lumped mass per DOF (kg)
  const Eigen::VectorXd& lumpedMass() const { return lumped_; }
  /// @return K + K_s, the constant stiffness of a linear structure with the
  /// springs on its diagonal, or nullptr when the structure has no constant K
  const SparseMatrix* stiffness() const { return stiffness_; }

  /// @return true when the model has external loads (else F_ext = 0 always)
  bool hasExternal() const { return has_external_; }
  /// @return true when the model has drag
  bool hasDrag() const { return has_drag_; }
  /// @return true when the model has springs to the ground
  bool hasSprings() const { return !model_.springs.empty(); }
  /// @return true when the model has mass-proportional damping (time.damping > 0)
  bool hasDamping() const { return model_.time.damping > 0; }
  /// @return true when the model has rigid surfaces in contact
  bool hasContact() const { return !model_.contact.empty(); }
  /// @return the rigid sets (DOFs with one acceleration)
  const std::vector<RigidSet>& rigidSets() const { return model_.rigid; }

  /// Sets the step of the scheme (s): external() then gives each
  /// time-dependent load's mean over [t - @p dt / 2, t + @p dt / 2] (from 0
  /// at the start; see LoadTime), the interval a force at t_n stands for,
  /// so that every step receives its interval's impulse and the steps
  /// together the loads' whole impulse. 0: values at t. The contact's
  /// friction caps a slip at what one step of @p dt stops.
  void setStep(double dt);

  /// f = F_ext(t) at displacements @p u (N).
  void external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// f = F_drag at displacements @p u and velocities @p v (N).
  void drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& f) const;
  /// f = F_s, the springs' force at displacements @p u (N).
  void springs(const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// The contact forces of the rigid surfaces (loads/contact.hpp) at
  /// membrane displacements @p u and velocities @p v, the surfaces'
  /// displacements @p su and velocities @p sv, into @p out.
  void contact(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& su,
               const Eigen::VectorXd& sv, ContactResult& out) const;
  /// Every force but the reactions at time @p t, displacements @p u,
  /// velocities @p v, surfaces' motion @p su, @p sv, into @p f: external,
  /// drag, springs, damping, contact (each when the model has it) and the
  /// internal force. Without loads or drag their members are set to zero
  /// once (when not yet of the right size) and then left alone.
  void forces(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
              const Eigen::VectorXd& su, const Eigen::VectorXd& sv, StateForces& f) const;
  /// f.reaction = R = (M a + f_int) - F_ext - F_drag - F_s - F_damp - F_c at
  /// the constrained DOFs, where @p inertia holds (M a + f_int) there in
  /// constraints() order, from the scheme (which knows its mass and its
  /// internal force); f's other members are the forces of the same state.
  void reactions(const Eigen::VectorXd& inertia, StateForces& f) const;

  /// Adds one step to @p works: the increment @p du and the forces @p f0 at
  /// its start and @p f1 at its end (the trapezoidal rule of energy.hpp).
  void addWorks(Works& works, const Eigen::VectorXd& du, const StateForces& f0,
                const StateForces& f1) const;
  /// @return reactions summed per constraint set, then the springs' force
  /// on the structure per spring set at @p u, then each rigid surface's
  /// contact force on the membrane, from the forces @p f (N)
  std::vector<Eigen::Vector3d> reactionSums(const StateForces& f, const Eigen::VectorXd& u) const;
  /// @return the names of reactionSums()'s entries
  std::vector<std::string> reactionNames() const;
  /// @return the drag summed over all nodes in @p f (N)
  Eigen::Vector3d dragSum(const StateForces& f) const;

  /// @return the stable step of central differences with the lumped mass
  /// (s, no safety factor) at the initial state: the structure's, with the
  /// springs' and the contact penalties' stiffness (a spring k on a node of
  /// lumped mass m adds k / m to omega^2, so 2 / dt_s becomes
  /// sqrt((2 / dt_s)^2 + k / m))
  double stableStep() const;
  /// @return stableStep() at displacements @p u and the structure's
  /// committed history (Structure::currentStableStep)
  double currentStableStep(const Eigen::VectorXd& u) const;

private:
  /// @return the structure's stable step @p dt with the springs and penalties
  double withSprings(double dt) const;
  void addSurface(WorkKind kind, const LoadTime& when, const Eigen::VectorXd& u,
                  const Eigen::VectorXd& v, Eigen::VectorXd& f) const;

  const Model& model_;
  std::unique_ptr<Structure> structure_;
  ConstrainedDofs cons_;
  Eigen::VectorXd lumped_;         // row sums of M
  SparseMatrix stiffness_springs_; // K + K_s when the model has springs
  const SparseMatrix* stiffness_ = nullptr;
  double half_step_ = 0, step_ = 0; // setStep()
  bool has_external_ = false, has_drag_ = false;
};

} // namespace lamina::membrane
