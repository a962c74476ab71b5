#include "membrane/integrators/rigid_condensation.hpp"

#include <map>
#include <numeric>
#include <utility>

namespace lamina::membrane {

RigidCondensation::RigidCondensation(const std::vector<RigidSet>& sets, int ndof) {
  if (sets.empty())
    return;
  master_.resize(static_cast<size_t>(ndof));
  std::iota(master_.begin(), master_.end(), 0);
  for (const auto& s : sets) {
    sets_.push_back(s.dofs);
    for (int d : s.dofs)
      master_[static_cast<size_t>(d)] = s.dofs.front();
  }
}

SparseMatrix RigidCondensation::condense(const SparseMatrix& A) const {
  if (empty())
    return A;
  // (T^T A T)_{IJ} = sum of A_ij over the DOFs i of I and j of J; slaves
  // keep only a unit diagonal. Summed into a map of 3x3 node blocks so that
  // every touched block is stored in full (the block solver's pattern).
  std::map<std::pair<int, int>, Eigen::Matrix3d> blocks;
  auto at = [&blocks](int i, int j) -> double& {
    auto it = blocks.try_emplace({i / 3, j / 3}, Eigen::Matrix3d::Zero()).first;
    return it->second(i % 3, j % 3);
  };
  for (int i = 0; i < A.outerSize(); ++i)
    for (SparseMatrix::InnerIterator it(A, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      at(master_[static_cast<size_t>(i)], master_[static_cast<size_t>(j)]) += it.value();
    }
  for (int i = 0; i < static_cast<int>(master_.size()); ++i)
    if (master_[static_cast<size_t>(i)] != i)
      at(i, i) = 1.0; // a slave's row and column held nothing else
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(9 * blocks.size());
  for (const auto& [ij, b] : blocks)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        t.emplace_back(3 * ij.first + r, 3 * ij.second + c, b(r, c));
  SparseMatrix C(A.rows(), A.cols());
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

void RigidCondensation::restrict(Eigen::VectorXd& b) const {
  for (const auto& s : sets_) {
    double sum = 0;
    for (int d : s)
      sum += b[d];
    for (int d : s)
      b[d] = 0;
    b[s.front()] = sum;
  }
}

void RigidCondensation::expand(Eigen::VectorXd& a) const {
  for (const auto& s : sets_)
    for (int d : s)
      a[d] = a[s.front()];
}

void RigidCondensation::zeroSlaves(Eigen::VectorXd& x) const {
  for (const auto& s : sets_)
    for (size_t k = 1; k < s.size(); ++k)
      x[s[k]] = 0;
}

} // namespace lamina::membrane
