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

#include <Eigen/Dense>

namespace lamina::membrane {

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
  /// @return the constant stiffness K (f_int = K u) of a linear model, else nullptr
  virtual const SparseMatrix* stiffness() const { return nullptr; }
  /// @return seconds spent building the model's matrices
  virtual double setupSeconds() const { return 0; }
};

} // namespace lamina::membrane
