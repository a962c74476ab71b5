#pragma once
/// @file assembly.hpp
/// @brief Element matrices of the membrane triangle (membrane paper section 3)
/// and the global stiffness and mass matrices.
///
/// DOF numbering: node-major, dof = 3 * node + c with c = 0 (u), 1 (v), 2 (w).
/// Strain in lamina order eps = [u_x, v_y, 0, u_y + v_x, w_y, w_x] (eqs. 12-14).

#include "membrane/model/mesh.hpp"
#include "membrane/model/section.hpp"

#include <Eigen/Sparse>

#include <vector>

namespace lamina::membrane {

/// Row-major sparse matrix used for all global operators (fast parallel SpMV).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
/// 6 x 9 strain-displacement matrix of one triangle.
using Matrix69 = Eigen::Matrix<double, 6, 9>;
/// 9 x 9 element matrix.
using Matrix9 = Eigen::Matrix<double, 9, 9>;

/// B of eqs. (12)-(14) for triangle @p e (constant over the element).
Matrix69 strainMatrix(const Mesh& mesh, int e);
/// Ke = h A B^T D B (eq. 23, constant strain).
Matrix9 elementStiffness(const Mesh& mesh, int e, const Section& s);
/// Consistent Me = rho h int N^T N (eq. 24): rho h A / 12 (1 + delta_ij) per component.
Matrix9 elementMass(const Mesh& mesh, int e, const Section& s, bool lumped);
/// Gradient inertia of micro-inertia, M_D,e = h A B^T (zeta^2 D) B (constant
/// strain): the kinetic energy of the strain rate, eps'.(zeta^2 D) eps'/2.
Matrix9 elementMicroMass(const Mesh& mesh, int e, const Section& s);

/// Global K and M (eqs. 26-27) with the same sparsity pattern (3x3 node blocks).
struct GlobalMatrices {
  SparseMatrix K;  ///< stiffness, N/m
  SparseMatrix M;  ///< mass, kg, including M_D
  SparseMatrix MD; ///< the micro-inertia part M_D of M (kg); 0 x 0 when no section has one
};

/// Assembles K and M over all triangles; section of triangle e is
/// sections[mesh.region_of[e]]. Sections with micro-inertia add M_D to M
/// (consistent even with a lumped rho-mass: M_D couples neighbours by
/// nature). Uses OpenMP over elements when available.
GlobalMatrices assemble(const Mesh& mesh, const std::vector<Section>& sections, bool lumped);

/// Tributary area of each node: sum over its triangles of A_e / 3 (m^2).
std::vector<double> nodalAreas(const Mesh& mesh);

/// y = A x with rows split over OpenMP threads (each row summed in a fixed
/// order: the result does not depend on the thread count).
void multiply(const SparseMatrix& A, const Eigen::VectorXd& x, Eigen::VectorXd& y);

} // namespace lamina::membrane
