#pragma once
/// @file case_builders.hpp
/// @brief The builders of a membrane case file, one per group of sections
/// (mesh, sections, time and outputs, constraints, loads), and the node and
/// element selectors they share. case_file.cpp's buildModel() dispatches to
/// them in the order the model needs; internal to membrane/io.

#include "core/toml_reader.hpp"
#include "membrane/io/material_sources.hpp"
#include "membrane/model/mesh.hpp"
#include "membrane/system/model.hpp"

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace lamina::membrane::case_io {

/// pi, for angles in degrees and the cos^2 load of eq. (31).
constexpr double kPi = 3.14159265358979323846;

/// The one selector key of a table: nodes (set name), box, at, region or all.
/// What a selector key selects by.
enum class SelectBy { Nodes, Box, At, Region, All };

/// A table's selection of nodes or elements.
struct Selector {
  SelectBy kind = SelectBy::All;                ///< what selects
  std::string name;                             ///< node set or region name
  std::array<double, 4> box{};                  ///< xmin, xmax, ymin, ymax (m)
  Eigen::Vector2d at = Eigen::Vector2d::Zero(); ///< a point on the mesh (m)
  std::string key;                              ///< the key that selected, for errors
};

// case_select.cpp: reading points, directions and selections.

/// @return the point [x, y] at @p key of @p r
Eigen::Vector2d readPoint(const core::TableReader& r, const std::string& key);
/// @return the unit `direction` or the `inclination_deg` from +z towards +x, else @p fallback
Eigen::Vector3d readDirection(const core::TableReader& r, const Eigen::Vector3d& fallback);
/// @return the one selector key of @p r
Selector readSelector(const core::TableReader& r);
/// @return readSelector(@p r), or everything when @p r gives no selector key
Selector readSelectorOrAll(const core::TableReader& r);
/// @return the index of region @p name of @p m; an error at @p key of @p r otherwise
int regionIndex(const Mesh& m, const std::string& name, const core::TableReader& r,
                const std::string& key);
/// @return the node of @p m at @p p (within its longest edge); an error at @p key otherwise
int nodeAt(const Mesh& m, const Eigen::Vector2d& p, const core::TableReader& r,
           const std::string& key);
/// @return the nodes of @p m that @p s selects (not empty; errors name @p r's keys)
std::vector<int> selectNodes(const Mesh& m, const Selector& s, const core::TableReader& r);
/// @return the elements of @p m that @p s selects (not empty; errors name @p r's keys)
std::vector<int> selectElements(const Mesh& m, const Selector& s, const core::TableReader& r);
/// @return the component indices of `components` (a subset of "xyz")
std::vector<int> readComponents(const core::TableReader& r);

// The builders, one per group of case sections.

/// [mesh] (case_mesh.cpp): a structured rectangle or a gmsh file relative to @p case_path.
Mesh readMesh(const core::TableReader& r, const std::filesystem::path& case_path);
/// [[section]] (case_sections.cpp): one per region; a section without
/// `region` covers every region left.
void readSections(const core::TableReader& root, const MaterialSources& sources, Model& model);
/// [time], [solver] and [output] (case_settings.cpp).
void readTimeAndOutput(const core::TableReader& root, Model& model);
/// Refuses what only the explicit integrator takes (rigid surfaces) under
/// Newmark (case_settings.cpp).
void checkIntegrator(const core::TableReader& root, const Model& model);
/// [[probe]] (case_settings.cpp).
void readProbes(const core::TableReader& root, Model& model);
/// [[fixed]] and [[strike]] (case_constraints.cpp); @return the constraint
/// owning each DOF (-1: free).
std::vector<int> readConstraints(const core::TableReader& root, Model& model);
/// [[spring]] (case_constraints.cpp): linear springs from the selected nodes to the ground.
void readSprings(const core::TableReader& root, Model& model);
/// [[rigid]] (case_constraints.cpp): the selected nodes translate together;
/// @p owner is readConstraints()' DOF owner list, extended.
void readRigidSets(const core::TableReader& root, Model& model, std::vector<int>& owner);
/// [[rigid_surface]] (case_contact.cpp): rigid bodies the membrane rests
/// on; after the constraints and springs (their names must differ).
void readRigidSurfaces(const core::TableReader& root, Model& model);
/// [initial] (case_constraints.cpp): initial velocity (optional).
void readInitial(const core::TableReader& root, Model& model);
/// [[load]], [[point_mass]] and [gravity] (case_loads.cpp).
void readLoads(const core::TableReader& root, Model& model);
/// [[blast]] (case_loads.cpp); @p path is the case file (CSV histories are relative to it).
void readBlasts(const core::TableReader& root, Model& model, const std::filesystem::path& path);
/// [[drag]] (case_loads.cpp): on surface regions.
void readDrags(const core::TableReader& root, Model& model);

} // namespace lamina::membrane::case_io
