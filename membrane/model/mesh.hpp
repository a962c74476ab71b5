#pragma once
/// @file mesh.hpp
/// @brief Triangle meshes of the membrane, flat or curved surfaces in 3D:
/// the built-in structured rectangle (x-y plane) here, gmsh files (.msh,
/// .geo) through membrane/io/gmsh_reader.hpp.
///
/// Contract: on exit every triangle has three distinct node indices, a
/// positive area and a region index into `regions`. A flat mesh (all z = 0,
/// `z` empty) has its triangles counter-clockwise seen from +z; a curved one
/// keeps gmsh's orientation. Plan quantities (area(), centroid(), selectors)
/// use (x, y); point() and area3() the 3D position. Boundary node sets are named: physical curves
/// of a gmsh file, or "left", "right", "bottom", "top", "edges" for the structured rectangle.

#include "core/error.hpp"

#include <Eigen/Dense>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace lamina::membrane {

/// A linear-triangle mesh of the undeformed membrane.
struct Mesh {
  std::vector<Eigen::Vector2d> nodes;                ///< initial coordinates (x0, y0), m
  std::vector<double> z;                             ///< initial z0 per node (empty: all 0)
  std::vector<std::array<int, 3>> triangles;         ///< node indices, counter-clockwise
  std::vector<int> region_of;                        ///< region index of each triangle
  std::vector<std::string> regions;                  ///< region names ("all" for the rectangle)
  std::map<std::string, std::vector<int>> node_sets; ///< named boundary node sets (sorted)
  std::string source;                                ///< file name or "structured"
  /// Per node: the user's node number (the gmsh node tag); empty: the index
  /// itself (structured rectangle). Runs renumber gmsh meshes (mesh_ordering.hpp).
  std::vector<std::size_t> node_id;
  /// Per triangle: the user's element number (the gmsh element tag); empty: the index.
  std::vector<std::size_t> element_id;

  /// @return the user's number of node @p i (node_id, else @p i): what messages and outputs print
  std::size_t nodeLabel(int i) const { return node_id.empty() ? std::size_t(i) : node_id[i]; }
  /// @return the user's number of triangle @p e (element_id, else @p e)
  std::size_t elementLabel(int e) const {
    return element_id.empty() ? std::size_t(e) : element_id[e];
  }
  /// @return the number of nodes
  int numNodes() const { return static_cast<int>(nodes.size()); }
  /// @return the number of triangles
  int numElements() const { return static_cast<int>(triangles.size()); }
  /// @return the plan area of triangle @p e (m^2, > 0 on a flat mesh)
  double area(int e) const;
  /// @return the initial 3D position of node @p i
  Eigen::Vector3d point(int i) const {
    return {nodes[i].x(), nodes[i].y(), z.empty() ? 0.0 : z[i]};
  }
  /// @return the true (3D) area of triangle @p e (m^2)
  double area3(int e) const;
  /// @return true when every node lies in the plane z = 0
  bool flat() const { return z.empty(); }
  /// @return the centroid of triangle @p e
  Eigen::Vector2d centroid(int e) const;
  /// @return the index of the node nearest to @p p (lowest index on ties)
  int nearestNode(const Eigen::Vector2d& p) const;
  /// @return the bounding box [xmin, xmax, ymin, ymax]
  std::array<double, 4> bounds() const;
  /// @return the largest edge length of all triangles
  double maxEdge() const;
};

/// The paper's structured grid (section 4): a rectangle [0,Lx] x [0,Ly] of
/// nx x ny squares, each split in two triangles by the diagonal from its
/// lower-left to its upper-right corner. One region "all".
Mesh structuredRectangle(double Lx, double Ly, int nx, int ny);

/// Memory a run needs per mesh node, bytes: peak resident size of `membrane
/// run` (CG solver) grows by 4.4 kB per node between nx = 100 and nx = 300
/// of cases/membrane/case3.toml (/usr/bin/time -f %M); 5 kB with margin.
inline constexpr double kRunBytesPerNode = 5e3;
/// Most nodes of a mesh: 3 DOF per node are indexed by int.
inline constexpr double kMaxNodes = 2e8;
/// Most time steps of a run (round(t_end / dt)); a longer run is refused.
inline constexpr double kMaxSteps = 1e8;

/// Refuses (lamina::Error with @p context) a mesh of @p nodes nodes that
/// exceeds kMaxNodes or whose run would need more memory than available
/// (kRunBytesPerNode each); @p what names the mesh in the message.
void requireRunMemory(double nodes, const std::string& what, const ErrorContext& context);

/// Renumbers the nodes of @p mesh: node i becomes @p old_to_new[i], or is
/// dropped where that is -1 (no triangle may use it; the new numbers are
/// 0 .. kept - 1). Coordinates, z, node_id (the user's numbers, which the
/// nodes keep), triangles and node sets follow; node sets come out sorted.
void renumberNodes(Mesh& mesh, const std::vector<int>& old_to_new);

/// Orients triangles counter-clockwise and checks the mesh (no degenerate
/// triangle, indices in range). Throws lamina::Error naming @p mesh.source.
void finalizeMesh(Mesh& mesh);

} // namespace lamina::membrane
