#include "membrane/model/mesh_ordering.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace lamina::membrane {

namespace {
using Graph =
    boost::adjacency_list<boost::setS, boost::vecS, boost::undirectedS,
                          boost::property<boost::vertex_color_t, boost::default_color_type,
                                          boost::property<boost::vertex_degree_t, int>>>;
} // namespace

void orderForLocality(Mesh& mesh) {
  const int n = mesh.numNodes(), ne = mesh.numElements();
  Graph g(static_cast<std::size_t>(n));
  for (const auto& t : mesh.triangles)
    for (int a = 0; a < 3; ++a)
      boost::add_edge(static_cast<std::size_t>(t[a]), static_cast<std::size_t>(t[(a + 1) % 3]), g);
  std::vector<std::size_t> order(static_cast<std::size_t>(n)); // new -> old
  boost::cuthill_mckee_ordering(g, order.rbegin(), boost::get(boost::vertex_color, g),
                                boost::make_degree_map(g));
  std::vector<int> renum(static_cast<std::size_t>(n)); // old -> new
  for (int k = 0; k < n; ++k)
    renum[order[k]] = k;
  renumberNodes(mesh, renum);
  std::vector<int> eorder(ne);
  std::iota(eorder.begin(), eorder.end(), 0);
  auto lowest = [&](int e) {
    const auto& t = mesh.triangles[e];
    return std::min({t[0], t[1], t[2]});
  };
  std::stable_sort(eorder.begin(), eorder.end(),
                   [&](int a, int b) { return lowest(a) < lowest(b); });
  std::vector<std::array<int, 3>> tri(ne);
  std::vector<int> region(ne);
  std::vector<std::size_t> element_id(ne);
  for (int k = 0; k < ne; ++k) {
    tri[k] = mesh.triangles[eorder[k]];
    region[k] = mesh.region_of[eorder[k]];
    element_id[k] = mesh.elementLabel(eorder[k]);
  }
  mesh.triangles = std::move(tri);
  mesh.region_of = std::move(region);
  mesh.element_id = std::move(element_id);
}

int nodeBandwidth(const Mesh& mesh) {
  int b = 0;
  for (const auto& t : mesh.triangles)
    for (int a = 0; a < 3; ++a)
      b = std::max(b, std::abs(t[a] - t[(a + 1) % 3]));
  return b;
}

} // namespace lamina::membrane
