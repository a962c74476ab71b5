// Node order for locality (membrane/model/mesh_ordering.hpp): reverse
// Cuthill-McKee brings a scrambled grid's bandwidth down to the bound of a
// breadth-first level structure, the renumbered mesh is the same mesh (every
// node, triangle and node set where it was, the user's numbers kept), a run
// on it gives the run in the file's order to round-off, the field file maps
// its nodes back to the gmsh tags, and reading a gmsh mesh leaves OpenMP's
// thread count as it was.
#include "helpers.hpp"

#include "core/hdf5_file.hpp"
#include "membrane/io/gmsh_reader.hpp"
#include "membrane/model/mesh_ordering.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <map>
#include <numeric>
#include <random>
#include <set>

using namespace lamina;
using namespace lamina::membrane;

namespace {

/// @p m with its nodes numbered by the random permutation of seed @p seed.
Mesh scrambled(const Mesh& m, unsigned seed) {
  std::vector<int> perm(m.numNodes()); // old -> new
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  Mesh s = m;
  renumberNodes(s, perm);
  s.node_id.clear(); // a mesh as a user gives it: its numbers are its indices
  return s;
}

/// Expects @p ordered to be @p original renumbered: node k of @p ordered is
/// node node_id[k] of @p original (labels of @p original = its indices),
/// triangle e is triangle element_id[e] with the same corners in the same
/// order, node sets hold the same points, every area keeps its sign.
void expectSameMesh(const Mesh& original, const Mesh& ordered) {
  ASSERT_EQ(ordered.numNodes(), original.numNodes());
  ASSERT_EQ(ordered.numElements(), original.numElements());
  std::set<std::size_t> seen(ordered.node_id.begin(), ordered.node_id.end());
  EXPECT_EQ(seen.size(), std::size_t(original.numNodes())); // a permutation
  for (int k = 0; k < ordered.numNodes(); ++k)
    EXPECT_EQ(ordered.nodes[k], original.nodes[ordered.node_id[k]]);
  for (int e = 0; e < ordered.numElements(); ++e) {
    const auto& t = ordered.triangles[e];
    const auto& o = original.triangles[ordered.element_id[e]];
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(ordered.node_id[t[a]], std::size_t(o[a]));
    EXPECT_EQ(ordered.region_of[e], original.region_of[ordered.element_id[e]]);
    EXPECT_GT(ordered.area(e), 0);
  }
  for (const auto& [name, set] : original.node_sets) {
    std::set<std::size_t> a(set.begin(), set.end()), b;
    for (int i : ordered.node_sets.at(name))
      b.insert(ordered.node_id[i]);
    EXPECT_EQ(a, b) << name;
  }
}

} // namespace

TEST(MeshOrdering, ScrambledGridGetsTheBandwidthOfALevelStructure) {
  const int nx = 40;
  const Mesh grid = structuredRectangle(1.0, 1.0, nx, nx);
  const Mesh s = scrambled(grid, 7);
  // The setup: a random numbering spreads neighbours over the whole mesh.
  EXPECT_GT(nodeBandwidth(s), s.numNodes() / 2);
  Mesh ordered = s;
  orderForLocality(ordered);
  expectSameMesh(s, ordered);
  // Reverse Cuthill-McKee numbers the nodes level by level of a breadth-first
  // search; an edge joins nodes of the same or adjacent levels, so the
  // bandwidth is below twice the largest level. A level of the (nx+1)^2 grid
  // graph is a ring of nodes at one graph distance, at most its perimeter
  // 4 (nx + 1) nodes: bound 8 (nx + 1) = 328, against ~1680 nodes.
  EXPECT_LE(nodeBandwidth(ordered), 8 * (nx + 1));
  // Elements follow their lowest node.
  for (int e = 1; e < ordered.numElements(); ++e) {
    const auto& a = ordered.triangles[e - 1];
    const auto& b = ordered.triangles[e];
    EXPECT_LE(std::min({a[0], a[1], a[2]}), std::min({b[0], b[1], b[2]}));
  }
}

TEST(MeshOrdering, GmshMeshKeepsItsTags) {
  const Mesh file_order = readGmsh(test::sourcePath("cases/meshes/circle.geo"));
  ASSERT_EQ(file_order.node_id.size(), std::size_t(file_order.numNodes()));
  ASSERT_EQ(file_order.element_id.size(), std::size_t(file_order.numElements()));
  Mesh ordered = file_order;
  orderForLocality(ordered);
  // Every node keeps its gmsh tag and position, every triangle its tag and corners.
  std::map<std::size_t, int> by_tag;
  for (int i = 0; i < file_order.numNodes(); ++i)
    by_tag[file_order.node_id[i]] = i;
  std::map<std::size_t, int> element_by_tag;
  for (int e = 0; e < file_order.numElements(); ++e)
    element_by_tag[file_order.element_id[e]] = e;
  for (int k = 0; k < ordered.numNodes(); ++k)
    EXPECT_EQ(ordered.nodes[k], file_order.nodes[by_tag.at(ordered.node_id[k])]);
  for (int e = 0; e < ordered.numElements(); ++e) {
    const auto& o = file_order.triangles[element_by_tag.at(ordered.element_id[e])];
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(ordered.node_id[ordered.triangles[e][a]], file_order.node_id[o[a]]);
  }
  EXPECT_LT(nodeBandwidth(ordered), nodeBandwidth(file_order));
}

TEST(MeshOrdering, ReadingAGmshMeshKeepsOpenMPsThreadCount) {
  // gmsh's initialize and finalize set OpenMP's thread count to gmsh's own
  // (1): every gmsh case then ran on one core.
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  readGmsh(test::sourcePath("cases/meshes/circle.geo"));
  EXPECT_EQ(omp_get_max_threads(), 2);
  omp_set_num_threads(before);
}

TEST(MeshOrdering, RenumberedRunEqualsTheRunInFileOrder) {
  const std::string strike = "[solver]\ntype = \"cholesky\"\n[[strike]]\nat = [0.0, 0.0]\n"
                             "speed = 10.0\n";
  const Model rcm = test::modelFromText(test::anisotropicCircle(1.0) + strike);
  const Model file =
      test::modelFromText(test::anisotropicCircle(1.0, "renumber = \"none\"\n") + strike);
  ASSERT_NE(rcm.mesh.triangles, file.mesh.triangles); // the orders differ
  std::map<std::size_t, int> in_file;
  for (int i = 0; i < file.mesh.numNodes(); ++i)
    in_file[file.mesh.nodeLabel(i)] = i;
  Simulation a(rcm), b(file);
  double diff = 0, scale = 0;
  for (int s = 0; s < 40; ++s) {
    a.step();
    b.step();
    for (int i = 0; i < rcm.mesh.numNodes(); ++i) {
      const int j = in_file.at(rcm.mesh.nodeLabel(i));
      diff =
          std::max(diff, (a.u().segment<3>(3 * i) - b.u().segment<3>(3 * j)).cwiseAbs().maxCoeff());
    }
    scale = std::max(scale, b.u().cwiseAbs().maxCoeff());
  }
  ASSERT_GT(scale, 0);
  // Both runs solve the same systems, permuted, by a factorization: they
  // differ by the round-off of assembly and solve in another order, a few
  // eps times the condition number of A = M + tau^2/4 K (of order 10 at this
  // step), accumulated over 40 steps: far below 1e-11 of the motion.
  EXPECT_LT(diff / scale, 1e-11);
}

TEST(MeshOrdering, FieldFileMapsNodesAndElementsToTheMeshFile) {
  const Model m = test::modelFromText(
      test::anisotropicCircle(4.0e-7) + "[output]\nfield_every = 1\n", "ordering.toml");
  RunOptions opt;
  opt.out_dir = test::tempPath("lamina-membrane-ordering");
  opt.quiet = true;
  std::filesystem::remove_all(opt.out_dir);
  runModel(m, opt);
  const core::H5File h5(opt.out_dir / "ordering.h5", core::H5File::Mode::ReadOnly);
  std::vector<std::uint64_t> dims;
  const std::vector<std::int32_t> nodes = h5.readInts("/mesh/node_id", dims);
  ASSERT_EQ(nodes.size(), std::size_t(m.mesh.numNodes()));
  const std::vector<std::int32_t> elements = h5.readInts("/mesh/element_id", dims);
  ASSERT_EQ(elements.size(), std::size_t(m.mesh.numElements()));
  // The tags of a fresh gmsh mesh of circle.geo, in the run's order.
  const Mesh file_order = readGmsh(test::sourcePath("cases/meshes/circle.geo"));
  EXPECT_EQ(std::set<std::int32_t>(nodes.begin(), nodes.end()),
            std::set<std::int32_t>(file_order.node_id.begin(), file_order.node_id.end()));
  // Row i of /mesh/geometry is the node gmsh calls nodes[i]; the corners of
  // row e of /mesh/topology are those of the triangle gmsh calls elements[e].
  const std::vector<double> xyz = h5.readDoubles("/mesh/geometry", dims);
  const std::vector<std::int32_t> topology = h5.readInts("/mesh/topology", dims);
  std::map<std::size_t, int> node_of_tag, element_of_tag;
  for (int i = 0; i < file_order.numNodes(); ++i)
    node_of_tag[file_order.node_id[i]] = i;
  for (int e = 0; e < file_order.numElements(); ++e)
    element_of_tag[file_order.element_id[e]] = e;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d p = file_order.point(node_of_tag.at(std::size_t(nodes[i])));
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(xyz[3 * i + c], p[c]);
  }
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto& t = file_order.triangles[element_of_tag.at(std::size_t(elements[e]))];
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(std::size_t(nodes[topology[3 * e + a]]), file_order.node_id[t[a]]);
  }
  std::filesystem::remove_all(opt.out_dir);
}
