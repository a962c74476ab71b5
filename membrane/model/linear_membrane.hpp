#pragma once
/// @file linear_membrane.hpp
/// @brief The membrane paper's model: flat triangles in the x-y plane, small
/// displacements, f_int = K u with K and M of eqs. (23)-(27).

#include "membrane/model/block_matrix.hpp"
#include "membrane/model/body.hpp"
#include "membrane/model/structure.hpp"

#include <memory>

namespace lamina::membrane {

/// K and M assembled once (assembly.hpp); point masses added to M.
class LinearMembrane final : public Structure {
public:
  /// Assembles K and M of @p body (the lumped, row-sum, mass when @p lumped, else
  /// the consistent one); keeps a reference to @p body.
  /// Throws lamina::Error naming the section when a section's law is not
  /// linear (Section::isLinear): only the large-deflection model steps one.
  LinearMembrane(const Body& body, bool lumped);
  int numDofs() const override { return static_cast<int>(K_.rows()); }
  const SparseMatrix& mass() const override { return M_; }
  /// f = K u (3x3-block product; shared stencil rows on uniform meshes).
  /// The blocks are built on the first call: do not call from two threads.
  void internalForce(const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  /// @return u.Ku / 2
  double strainEnergy(const Eigen::VectorXd& u) const override;
  const SparseMatrix* stiffness() const override { return &K_; }
  /// L_e over the fastest wave of the section's D (acoustic tensor of the 6 strains)
  double stableStep() const override;
  /// "strain" and "stress" (6 per element, lamina order; sigma = D eps, eq. 15)
  std::vector<CellField> cellFields(const Eigen::VectorXd& u) const override;
  const SparseMatrix* microMass() const override { return MD_.rows() ? &MD_ : nullptr; }
  double setupSeconds() const override { return assembly_s_; }

private:
  const Body& body_;
  SparseMatrix K_, M_, MD_;
  mutable std::unique_ptr<BlockMatrix> Kb_; // for internalForce (explicit runs only)
  double assembly_s_ = 0;
};

} // namespace lamina::membrane
