#pragma once
/// @file body.hpp
/// @brief The membrane as a body: its mesh, the section of each region and
/// the point masses. What a structure (structure.hpp: LinearMembrane,
/// LargeDeflection) is built from; it knows nothing of what acts on it
/// (constraints, loads, drag, springs: system/model.hpp gathers those).

#include "membrane/model/mesh.hpp"
#include "membrane/model/section.hpp"

#include <utility>
#include <vector>

namespace lamina::membrane {

/// The mesh, its sections and its point masses.
struct Body {
  Mesh mesh;                                        ///< the mesh
  std::vector<Section> sections;                    ///< one per mesh region
  std::vector<std::pair<int, double>> point_masses; ///< (node, kg)
  /// @return the number of degrees of freedom, 3 per node
  int numDofs() const { return 3 * mesh.numNodes(); }
};

} // namespace lamina::membrane
