#pragma once
/// @file rigid_condensation.hpp
/// @brief Rigid translating sets ([[rigid]]) in the implicit scheme, exactly:
/// condensation of the accelerations a = T a_r, where T ties every DOF of a
/// set to its first DOF (the master) and leaves the other DOFs alone.
///
/// The Newmark step solves A a = b; with the set's DOFs tied it solves
///   (T^T A T) a_r = T^T b,  a = T a_r,
/// the virtual work of the step restricted to motions in which the set's
/// DOFs accelerate together: the master's row is the sum of the set's rows
/// (total force over the total of A's rows, the explicit scheme's "total
/// force over total mass" when A is the lumped mass), the constraint forces
/// inside the set sum to zero. The matrices keep their size (3 per node):
/// the slaves' rows and columns of T^T A T become the identity with a zero
/// right-hand side, and expand() copies the master's value back to them, so
/// the step solver's 3x3 node blocks stay (completed with explicit zeros
/// where the master's row gains the slaves' neighbours).
///
/// u and v of the set follow from a through Newmark's correctors: DOFs that
/// start with equal displacements and velocities keep them equal.

#include "membrane/model/assembly.hpp"
#include "membrane/system/model.hpp"

#include <Eigen/Dense>

#include <vector>

namespace lamina::membrane {

/// The condensation a = T a_r of a model's rigid sets.
class RigidCondensation {
public:
  /// T for @p sets on @p ndof DOFs (sets disjoint, at least one DOF each).
  RigidCondensation(const std::vector<RigidSet>& sets, int ndof);
  /// @return true when there is no set (every operation is the identity)
  bool empty() const { return master_.empty(); }
  /// @return T^T @p A T with identity rows and columns at the slaves, every
  /// touched 3x3 node block stored in full (symmetric positive definite
  /// when @p A is)
  SparseMatrix condense(const SparseMatrix& A) const;
  /// b <- T^T b with zeros at the slaves (a master takes its set's sum).
  void restrict(Eigen::VectorXd& b) const;
  /// a <- T a_r: every slave takes its master's value.
  void expand(Eigen::VectorXd& a) const;
  /// Zeros the slaves' entries of @p x (the condensed solution's value there).
  void zeroSlaves(Eigen::VectorXd& x) const;

private:
  std::vector<int> master_; ///< per DOF: its master (itself when not in a set)
  std::vector<std::vector<int>> sets_;
};

} // namespace lamina::membrane
