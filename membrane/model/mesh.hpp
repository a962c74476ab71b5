#pragma once
/// @file mesh.hpp
/// @brief Triangle meshes of the membrane in the x-y plane: the built-in
/// structured rectangle and gmsh files (.msh, .geo) read via the gmsh C++ API.
///
/// Contract: on exit every triangle has three distinct node indices, a
/// positive area (nodes reordered counter-clockwise) and a region index into
/// `regions`. Boundary node sets are named: physical curves of a gmsh file,
/// or "left", "right", "bottom", "top", "edges" for the structured rectangle.

#include <Eigen/Dense>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace lamina::membrane {

/// A linear-triangle mesh of the undeformed membrane (z = 0).
struct Mesh {
  std::vector<Eigen::Vector2d> nodes;                ///< initial coordinates (x0, y0), m
  std::vector<std::array<int, 3>> triangles;         ///< node indices, counter-clockwise
  std::vector<int> region_of;                        ///< region index of each triangle
  std::vector<std::string> regions;                  ///< region names ("all" for the rectangle)
  std::map<std::string, std::vector<int>> node_sets; ///< named boundary node sets (sorted)
  std::string source;                                ///< file name or "structured"

  /// @return the number of nodes
  int numNodes() const { return static_cast<int>(nodes.size()); }
  /// @return the number of triangles
  int numElements() const { return static_cast<int>(triangles.size()); }
  /// @return the area of triangle @p e (m^2, > 0)
  double area(int e) const;
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

/// Reads a 2D triangle mesh from a gmsh .msh file, or meshes a .geo file
/// (2D), through the gmsh C++ API. Physical surfaces become regions (a mesh
/// without physical surfaces has one region "all"); physical curves and
/// points become node sets. Throws lamina::Error naming the file when it is
/// missing, unreadable, or has no triangles.
Mesh readGmsh(const std::filesystem::path& path);

/// Orients triangles counter-clockwise and checks the mesh (no degenerate
/// triangle, indices in range). Throws lamina::Error naming @p mesh.source.
void finalizeMesh(Mesh& mesh);

} // namespace lamina::membrane
