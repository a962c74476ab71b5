#pragma once
/// @file structure.hpp
/// @brief The spatial discretization of a membrane as the time integrators
/// see it: a mass matrix M and an internal force f_int(u), so that the
/// semi-discrete equation of motion reads M a + f_int(u) = F(t, u, v) + R.
///
/// A model (the paper's linear membrane, the large-deflection fabric) is a
/// type behind this interface; an integrator that needs more (Newmark needs
/// the constant stiffness K) asks for it and refuses a model without it.

#include "membrane/model/assembly.hpp"
#include "membrane/model/failure.hpp"

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
};

} // namespace lamina::membrane
