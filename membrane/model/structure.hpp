#pragma once
/// @file structure.hpp
/// @brief The spatial discretization of a membrane as the time integrators
/// see it: a mass matrix M and an internal force f_int(u), so that the
/// semi-discrete equation of motion reads M a + f_int(u) = F(t, u, v) + R.
///
/// A model (the paper's linear membrane, the large-deflection fabric) is a
/// type behind this interface; an integrator that needs more (Newmark needs
/// the constant stiffness K) asks for it and refuses a model without it.
///
/// Material history: when a section's law carries state (hasHistory()), the
/// internal force depends on the path. The owner of the structure then
/// calls beginStep(t1, dt) before a step; internalForce(u) is the force at
/// t1 of one step from the committed history to displacements u (the trial
/// history is kept aside), commitStep() accepts the trial once the step is
/// finite, and strainEnergy(), cellFields(), checkFailure() and
/// inelasticDissipation() describe the committed history (their u must be
/// the displacements it was committed at). A structure without history
/// ignores all of this.

#include "membrane/model/assembly.hpp"
#include "membrane/model/failure.hpp"
#include "membrane/model/history.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace lamina::membrane {

/// A per-element output field (components per element, element-major).
struct CellField {
  std::string name;           ///< dataset name
  int components = 1;         ///< values per element
  std::vector<double> values; ///< elements x components
};

/// Mass and internal force of a membrane model.
class Structure {
public:
  virtual ~Structure() = default;
  /// @return the number of DOFs (3 per node)
  virtual int numDofs() const = 0;
  /// @return the mass matrix incl. point masses (kg); diagonal when lumped
  virtual const SparseMatrix& mass() const = 0;
  /// f = f_int(u), the internal (elastic) nodal force at displacements @p u (N).
  virtual void internalForce(const Eigen::VectorXd& u, Eigen::VectorXd& f) const = 0;
  /// @return the strain energy at displacements @p u (J)
  virtual double strainEnergy(const Eigen::VectorXd& u) const = 0;
  /// @return the micro-inertia part M_D of mass() (already in it), or
  /// nullptr when no section has micro-inertia
  virtual const SparseMatrix* microMass() const { return nullptr; }
  /// @return the constant stiffness K (f_int = K u) of a linear model, else nullptr
  virtual const SparseMatrix* stiffness() const { return nullptr; }
  /// @return true when strainEnergy() is a potential of the internal force
  /// (false: the bookkeeping integrates the internal work instead)
  virtual bool hasPotential() const { return true; }
  /// @return the stable step of explicit central differences with the
  /// lumped mass (s), before the safety factor: min over elements of the
  /// element length 2 A / (longest edge) over the fastest wave speed of its section
  virtual double stableStep() const = 0;
  /// @return the element fields written to the XDMF series at displacements @p u
  virtual std::vector<CellField> cellFields(const Eigen::VectorXd& u) const = 0;
  /// @return true when the model's current geometry is x = X + u (ParaView
  /// draws the deformed surface); false for the paper's small-displacement model
  virtual bool deformedGeometry() const { return false; }
  /// @return true when a section has a failure threshold
  virtual bool hasFailureThresholds() const { return false; }
  /// Marks in @p record the elements whose thresholds are crossed at time
  /// @p t and displacements @p u (no-op without thresholds).
  virtual void checkFailure(double t, const Eigen::VectorXd& u, FailureRecord& record) const {
    (void)t;
    (void)u;
    (void)record;
  }
  /// @return seconds spent building the model's matrices
  virtual double setupSeconds() const { return 0; }
  /// @return true when the internal force of the wrinkling law is neither the
  /// gradient of strainEnergy() nor accounted for by a law's dissipation (the
  /// tension-only projection of elastic sections): the bookkeeping then
  /// reports the internal work no energy holds as wrinkling dissipation
  virtual bool nonConservativeWrinkling() const { return false; }

  /// @return true when a section's law carries history (see the file comment)
  virtual bool hasHistory() const { return false; }
  /// Sets the step of the next internalForce() calls: from the committed
  /// history to time @p t1 (s) over @p dt (s, >= 0; 0 at the initial state).
  virtual void beginStep(double t1, double dt) {
    (void)t1;
    (void)dt;
  }
  /// Accepts the history of the last internalForce() call.
  virtual void commitStep() {}
  /// @return the inelastic dissipation of the committed history since t = 0 (J)
  virtual double inelasticDissipation() const { return 0; }
  /// @return the stable step at displacements @p u and the committed history
  /// (s, as stableStep()): for a structure whose stiffness changes with the
  /// state (a stretched fabric, GVBO stiffening in compression) it changes as
  /// the run goes
  virtual double currentStableStep(const Eigen::VectorXd& u) const {
    (void)u;
    return stableStep();
  }
  /// @return whether currentStableStep() can differ from stableStep(), so
  /// that an explicit run re-evaluates it
  virtual bool stateDependentStep() const { return hasHistory(); }
  /// Saves the committed history into @p h (keys of the structure's choosing).
  virtual void saveHistory(History& h) const { (void)h; }
  /// Restores what saveHistory() wrote, on a structure just built from the
  /// same model; throws lamina::Error naming a missing, mis-sized or
  /// out-of-range entry.
  virtual void restoreHistory(const History& h) { (void)h; }
};

} // namespace lamina::membrane
