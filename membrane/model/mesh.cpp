#include "membrane/model/mesh.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/resources.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace lamina::membrane {

double Mesh::area(int e) const {
  const auto& t = triangles[e];
  const Eigen::Vector2d a = nodes[t[1]] - nodes[t[0]], b = nodes[t[2]] - nodes[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

double Mesh::area3(int e) const {
  const auto& t = triangles[e];
  return 0.5 * (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0])).norm();
}

Eigen::Vector2d Mesh::centroid(int e) const {
  const auto& t = triangles[e];
  return (nodes[t[0]] + nodes[t[1]] + nodes[t[2]]) / 3.0;
}

int Mesh::nearestNode(const Eigen::Vector2d& p) const {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < numNodes(); ++i) {
    const double di = (nodes[i] - p).squaredNorm();
    // Ties (symmetric grids) go to the lowest user number, whatever the run's order.
    const bool tie = best >= 0 && !(di < d * (1 - 1e-12)) && di <= d * (1 + 1e-12);
    if (di < d * (1 - 1e-12) || (tie && nodeLabel(i) < nodeLabel(best))) {
      d = std::min(d, di);
      best = i;
    }
  }
  return best;
}

std::array<double, 4> Mesh::bounds() const {
  std::array<double, 4> b{
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& p : nodes) {
    b[0] = std::min(b[0], p.x());
    b[1] = std::max(b[1], p.x());
    b[2] = std::min(b[2], p.y());
    b[3] = std::max(b[3], p.y());
  }
  return b;
}

double Mesh::maxEdge() const {
  double h = 0;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k)
      h = std::max(h, (nodes[t[k]] - nodes[t[(k + 1) % 3]]).norm());
  return h;
}

void requireRunMemory(double nodes, const std::string& what, const ErrorContext& context) {
  if (!(nodes <= kMaxNodes))
    throw Error(what + " has " + core::formatShort(nodes) + " nodes; at most " +
                    core::formatShort(kMaxNodes),
                context);
  core::requireMemory(nodes * kRunBytesPerNode,
                      "a run on " + what + " (" + core::formatShort(nodes) + " nodes)", context);
}

void renumberNodes(Mesh& mesh, const std::vector<int>& old_to_new) {
  const auto kept = static_cast<std::size_t>(
      std::count_if(old_to_new.begin(), old_to_new.end(), [](int k) { return k >= 0; }));
  std::vector<Eigen::Vector2d> nodes(kept);
  std::vector<double> z(mesh.z.empty() ? 0 : kept);
  std::vector<std::size_t> node_id(kept);
  for (int i = 0; i < mesh.numNodes(); ++i) {
    const int k = old_to_new[i];
    if (k < 0)
      continue;
    nodes[k] = mesh.nodes[i];
    if (!z.empty())
      z[k] = mesh.z[i];
    node_id[k] = mesh.nodeLabel(i);
  }
  for (auto& t : mesh.triangles)
    for (int& i : t) {
      assert(old_to_new[i] >= 0 && "a triangle uses a dropped node");
      i = old_to_new[i];
    }
  for (auto& [name, set] : mesh.node_sets) {
    std::vector<int> renumbered;
    for (int i : set)
      if (old_to_new[i] >= 0)
        renumbered.push_back(old_to_new[i]);
    std::sort(renumbered.begin(), renumbered.end());
    set = std::move(renumbered);
  }
  mesh.nodes = std::move(nodes);
  mesh.z = std::move(z);
  mesh.node_id = std::move(node_id);
}

void finalizeMesh(Mesh& mesh) {
  LAMINA_CHECK(!mesh.triangles.empty(), mesh.source, ": mesh has no triangles");
  LAMINA_CHECK(mesh.region_of.size() == mesh.triangles.size(), mesh.source,
               ": region list does not match the triangles");
  const int n = mesh.numNodes();
  LAMINA_CHECK(mesh.z.empty() || static_cast<int>(mesh.z.size()) == n, mesh.source,
               ": z list does not match the nodes");
  if (std::all_of(mesh.z.begin(), mesh.z.end(), [](double v) { return v == 0.0; }))
    mesh.z.clear();
  for (int e = 0; e < mesh.numElements(); ++e) {
    auto& t = mesh.triangles[e];
    for (int k = 0; k < 3; ++k)
      LAMINA_CHECK(t[k] >= 0 && t[k] < n, mesh.source, ": triangle ", mesh.elementLabel(e),
                   " refers to a missing node");
    LAMINA_CHECK(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], mesh.source, ": triangle ",
                 mesh.elementLabel(e), " repeats a node");
    if (mesh.flat() && mesh.area(e) < 0)
      std::swap(t[1], t[2]);
    // Degenerate: area tiny compared with the square of its longest edge.
    double l2 = 0;
    for (int k = 0; k < 3; ++k)
      l2 = std::max(l2, (mesh.point(t[k]) - mesh.point(t[(k + 1) % 3])).squaredNorm());
    LAMINA_CHECK((mesh.flat() ? mesh.area(e) : mesh.area3(e)) > 1e-12 * l2, mesh.source,
                 ": triangle ", mesh.elementLabel(e), " is degenerate (zero area)");
  }
  for (auto& [name, set] : mesh.node_sets) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
}

Mesh structuredRectangle(double Lx, double Ly, int nx, int ny) {
  LAMINA_CHECK(Lx > 0 && Ly > 0, "structured mesh: lengths must be positive");
  LAMINA_CHECK(nx >= 1 && ny >= 1, "structured mesh: nx and ny must be >= 1");
  Mesh m;
  m.source = "structured";
  const int nxp = nx + 1;
  m.nodes.reserve(static_cast<size_t>(nxp) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      m.nodes.emplace_back(Lx * i / nx, Ly * j / ny);
  auto id = [nxp](int i, int j) { return j * nxp + i; };
  m.triangles.reserve(2 * static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // Square split by the diagonal (i,j)-(i+1,j+1), as in the paper's grid.
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.region_of.assign(m.triangles.size(), 0);
  m.regions = {"all"};
  auto& left = m.node_sets["left"];
  auto& right = m.node_sets["right"];
  auto& bottom = m.node_sets["bottom"];
  auto& top = m.node_sets["top"];
  for (int j = 0; j <= ny; ++j) {
    left.push_back(id(0, j));
    right.push_back(id(nx, j));
  }
  for (int i = 0; i <= nx; ++i) {
    bottom.push_back(id(i, 0));
    top.push_back(id(i, ny));
  }
  auto& edges = m.node_sets["edges"];
  for (const auto* s : {&left, &right, &bottom, &top})
    edges.insert(edges.end(), s->begin(), s->end());
  finalizeMesh(m);
  return m;
}

} // namespace lamina::membrane
