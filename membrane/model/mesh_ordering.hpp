#pragma once
/// @file mesh_ordering.hpp
/// @brief Node and element ordering of a mesh for memory locality.
///
/// A gmsh mesh numbers its nodes in the order the mesher made them: the
/// neighbours of a node are scattered over the whole node array, so every
/// product with K and every element loop of a step misses the cache. The
/// reverse Cuthill-McKee ordering (Boost.Graph) numbers the nodes of the
/// node graph (two nodes adjacent when a triangle holds both) level by
/// level from a peripheral node: the bandwidth of K, and so the distance in
/// memory between the nodes one row or one element touches, drops to about
/// the width of the mesh front. The elements are then sorted by their
/// smallest node, so an element loop walks the nodes in order too.
///
/// Contract: the mesh is valid (finalizeMesh); on exit the same mesh with
/// renumbered nodes and reordered elements: node sets, regions and triangle
/// orientation follow, and Mesh::node_id / Mesh::element_id keep what each
/// node and element was called before (the user's numbering).

#include "membrane/model/mesh.hpp"

namespace lamina::membrane {

/// Renumbers the nodes of @p mesh by reverse Cuthill-McKee and orders its
/// triangles by their smallest node (ties: the previous order).
void orderForLocality(Mesh& mesh);

/// @return the bandwidth of @p mesh's node graph: the largest |i - j| over
/// the node pairs of a triangle (the block bandwidth of K)
int nodeBandwidth(const Mesh& mesh);

} // namespace lamina::membrane
