#include "membrane/model/assembly.hpp"

#include <algorithm>

namespace lamina::membrane {

Matrix69 strainMatrix(const Mesh& mesh, int e) {
  const auto& t = mesh.triangles[e];
  const double A2 = 2 * mesh.area(e);
  Matrix69 B = Matrix69::Zero();
  for (int i = 0; i < 3; ++i) {
    const auto& pj = mesh.nodes[t[(i + 1) % 3]];
    const auto& pk = mesh.nodes[t[(i + 2) % 3]];
    // eq. (11): beta_i = dN_i/dx, gamma_i = dN_i/dy
    const double beta = (pj.y() - pk.y()) / A2;
    const double gamma = (pk.x() - pj.x()) / A2;
    const int c = 3 * i;
    B(0, c + 0) = beta;  // u_x
    B(1, c + 1) = gamma; // v_y
    B(3, c + 0) = gamma; // u_y + v_x
    B(3, c + 1) = beta;
    B(4, c + 2) = gamma; // w_y
    B(5, c + 2) = beta;  // w_x
  }
  return B;
}

Matrix9 elementStiffness(const Mesh& mesh, int e, const Section& s) {
  const Matrix69 B = strainMatrix(mesh, e);
  return s.thickness * mesh.area(e) * (B.transpose() * s.D * B);
}

Matrix9 elementMass(const Mesh& mesh, int e, const Section& s, bool lumped) {
  const double m = s.density * s.thickness * mesh.area(e);
  Matrix9 Me = Matrix9::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double v = lumped ? (i == j ? m / 3 : 0.0) : m / 12 * (i == j ? 2.0 : 1.0);
      for (int c = 0; c < 3; ++c)
        Me(3 * i + c, 3 * j + c) = v;
    }
  return Me;
}

Matrix9 elementMicroMass(const Mesh& mesh, int e, const Section& s) {
  const Matrix69 B = strainMatrix(mesh, e);
  return s.thickness * mesh.area(e) * (B.transpose() * s.dispersion * B);
}

namespace {
/// Below this many rows a product stays on one thread.
constexpr int kParallelRows = 30000;

/// Builds the node-block sparsity pattern (node adjacency incl. self) as CSR.
void nodeGraph(const Mesh& mesh, std::vector<int>& start, std::vector<int>& cols) {
  const int n = mesh.numNodes();
  std::vector<std::vector<int>> adj(n);
  for (const auto& t : mesh.triangles)
    for (int a : t)
      for (int b : t)
        adj[a].push_back(b);
  start.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    auto& v = adj[i];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    start[i + 1] = start[i] + static_cast<int>(v.size());
  }
  cols.resize(start[n]);
  for (int i = 0; i < n; ++i)
    std::copy(adj[i].begin(), adj[i].end(), cols.begin() + start[i]);
}

/// Empty row-major matrix with the scalar pattern of the 3x3-block node graph.
SparseMatrix blockPattern(int n, const std::vector<int>& start, const std::vector<int>& cols) {
  SparseMatrix A(3 * n, 3 * n);
  A.resizeNonZeros(9 * static_cast<Eigen::Index>(cols.size()));
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* val = A.valuePtr();
  int pos = 0;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      outer[3 * i + c] = pos;
      for (int k = start[i]; k < start[i + 1]; ++k)
        for (int d = 0; d < 3; ++d) {
          inner[pos] = 3 * cols[k] + d;
          val[pos++] = 0.0;
        }
    }
  outer[3 * n] = pos;
  return A;
}
} // namespace

GlobalMatrices assemble(const Mesh& mesh, const std::vector<Section>& sections, bool lumped) {
  const int n = mesh.numNodes();
  std::vector<int> start, cols;
  nodeGraph(mesh, start, cols);
  GlobalMatrices g;
  g.K = blockPattern(n, start, cols);
  g.M = g.K;
  bool micro = false;
  for (const Section& s : sections)
    micro = micro || s.hasMicroInertia();
  if (micro)
    g.MD = g.K;
  const int ne = mesh.numElements();
  // Scatter directly into the fixed pattern; atomics keep the element loop parallel.
  double* kv = g.K.valuePtr();
  double* mv = g.M.valuePtr();
  double* dv = micro ? g.MD.valuePtr() : nullptr;
  const int* outer = g.K.outerIndexPtr();
#pragma omp parallel for schedule(static) if (ne > 20000)
  for (int e = 0; e < ne; ++e) {
    const Section& s = sections[mesh.region_of[e]];
    const Matrix9 Ke = elementStiffness(mesh, e, s);
    Matrix9 Me = elementMass(mesh, e, s, lumped);
    const bool has_md = dv && s.hasMicroInertia();
    const Matrix9 MDe = has_md ? elementMicroMass(mesh, e, s) : Matrix9::Zero();
    Me += MDe;
    const auto& t = mesh.triangles[e];
    for (int a = 0; a < 3; ++a) {
      const int i = t[a];
      for (int b = 0; b < 3; ++b) {
        const int j = t[b];
        const int k = static_cast<int>(
            std::lower_bound(cols.begin() + start[i], cols.begin() + start[i + 1], j) -
            cols.begin() - start[i]);
        for (int c = 0; c < 3; ++c) {
          const int base = outer[3 * i + c] + 3 * k;
          for (int d = 0; d < 3; ++d) {
#pragma omp atomic
            kv[base + d] += Ke(3 * a + c, 3 * b + d);
#pragma omp atomic
            mv[base + d] += Me(3 * a + c, 3 * b + d);
            if (has_md) {
#pragma omp atomic
              dv[base + d] += MDe(3 * a + c, 3 * b + d);
            }
          }
        }
      }
    }
  }
  return g;
}

std::vector<double> nodalAreas(const Mesh& mesh) {
  std::vector<double> a(mesh.numNodes(), 0.0);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int i : mesh.triangles[e])
      a[i] += mesh.area(e) / 3;
  return a;
}

void multiply(const SparseMatrix& A, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int n = static_cast<int>(A.rows());
  y.resize(n);
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  const double* xp = x.data();
  double* yp = y.data();
#pragma omp parallel for schedule(static) if (n > kParallelRows)
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      s += val[k] * xp[inner[k]];
    yp[i] = s;
  }
}

} // namespace lamina::membrane
