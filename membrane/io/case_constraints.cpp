/// @file case_constraints.cpp
/// @brief [[fixed]], [[strike]], [[spring]], [[rigid]] and [initial] of a case.

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "membrane/loads/ground_springs.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

namespace lamina::membrane::case_io {

/// [[fixed]] and [[strike]]; @return the constraint owning each DOF (-1: free).
std::vector<int> readConstraints(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  const int ndof = 3 * mesh.numNodes();
  std::vector<int> owner(ndof, -1);
  auto addConstraint = [&](const core::TableReader& r, Constraint c, const std::vector<int>& nodes,
                           const std::string& comps, const Eigen::Vector3d& vel) {
    if (const std::string why = core::nameProblem(c.name); !why.empty())
      r.fail("name", "constraint set name " + why); // names CSV columns
    for (char ch : comps)
      if (ch != 'x' && ch != 'y' && ch != 'z')
        r.fail("components", "components is a subset of \"xyz\"");
    for (int node : nodes)
      for (int comp = 0; comp < 3; ++comp) {
        if (comps.find("xyz"[comp]) == std::string::npos)
          continue;
        const int dof = 3 * node + comp;
        if (owner[dof] >= 0)
          r.failHere("node " + std::to_string(model.mesh.nodeLabel(node)) +
                     " is already constrained by '" + model.constraints[owner[dof]].name + "'");
        owner[dof] = static_cast<int>(model.constraints.size());
        c.dofs.push_back(dof);
        c.amplitude.push_back(vel[comp]);
      }
    model.constraints.push_back(std::move(c));
  };
  for (const auto& r : root.tableArray("fixed")) {
    const Selector sel = readSelector(r);
    Constraint c;
    c.name = r.getString("name", sel.kind == SelectBy::Nodes
                                     ? sel.name
                                     : "fixed" + std::to_string(model.constraints.size()));
    addConstraint(r, std::move(c), selectNodes(mesh, sel, r), r.getString("components", "xyz"),
                  Eigen::Vector3d::Zero());
  }
  for (const auto& r : root.tableArray("strike")) {
    const Selector sel = readSelector(r);
    Constraint c;
    c.name = r.getString("name", "strike");
    const double speed = r.getDouble("speed");
    const Eigen::Vector3d dir = readDirection(r, Eigen::Vector3d::UnitZ());
    c.profile = TimeProfile::read(r);
    addConstraint(r, std::move(c), selectNodes(mesh, sel, r), "xyz", speed * dir);
  }

  return owner;
}

/// [initial]: an initial velocity (optional), uniform and/or one sine mode,
/// on the nodes of its selector (nodes, box, at, region, all; none: every node).
void readInitial(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  if (auto ini = root.optionalTable("initial")) {
    model.v0 = Eigen::VectorXd::Zero(3 * mesh.numNodes());
    const std::vector<int> nodes = selectNodes(mesh, readSelectorOrAll(*ini), *ini);
    if (ini->has("velocity") || !ini->has("mode")) {
      const auto v = ini->getDoubleArray("velocity");
      if (v.size() != 3)
        ini->fail("velocity", "expected [vx, vy, vz]");
      for (int i : nodes)
        for (int c = 0; c < 3; ++c)
          model.v0[3 * i + c] = v[c];
    }
    if (ini->has("mode")) {
      // v_z += V sin(m pi (x - xmin) / Lx) sin(n pi (y - ymin) / Ly) over the bounding box.
      const auto mn = ini->getDoubleArray("mode");
      if (mn.size() != 2 || mn[0] < 1 || mn[1] < 1 || mn[0] != std::floor(mn[0]) ||
          mn[1] != std::floor(mn[1]))
        ini->fail("mode", "expected [m, n], integers >= 1");
      const double V = ini->getDouble("mode_velocity");
      const auto [xmin, xmax, ymin, ymax] = mesh.bounds();
      for (int i : nodes)
        model.v0[3 * i + 2] += V *
                               std::sin(mn[0] * kPi * (mesh.nodes[i].x() - xmin) / (xmax - xmin)) *
                               std::sin(mn[1] * kPi * (mesh.nodes[i].y() - ymin) / (ymax - ymin));
    } else if (ini->has("mode_velocity")) {
      ini->fail("mode_velocity", "needs mode = [m, n]");
    }
  }
}

/// [[spring]]: linear springs from the selected nodes to the ground.
void readSprings(const core::TableReader& root, Model& model) {
  for (const auto& r : root.tableArray("spring")) {
    const double k = r.getDouble("stiffness");
    if (!(k > 0) || !std::isfinite(k))
      r.fail("stiffness", "spring stiffness must be > 0 (N/m per node)");
    const auto comps = readComponents(r);
    const auto nodes = selectNodes(model.mesh, readSelector(r), r);
    std::vector<int> dofs;
    for (int node : nodes)
      for (int c : comps)
        dofs.push_back(3 * node + c);
    model.springs.push_back(std::make_shared<GroundSprings>(
        r.getString("name", "spring" + std::to_string(model.springs.size())), dofs, k));
  }
}

/// [[rigid]]: the selected nodes translate together in each listed component
/// (a rigid frame); no DOF may also be constrained or in another set.
void readRigidSets(const core::TableReader& root, Model& model, std::vector<int>& owner) {
  for (const auto& r : root.tableArray("rigid")) {
    const std::string name = r.getString("name", "rigid" + std::to_string(model.rigid.size()));
    const auto comps = readComponents(r);
    const auto nodes = selectNodes(model.mesh, readSelector(r), r);
    if (nodes.size() < 2)
      r.failHere("a rigid set needs at least two nodes");
    for (int c : comps) {
      RigidSet set{name + "_" + "xyz" [c], {}};
      for (int node : nodes) {
        const int dof = 3 * node + c;
        if (owner[dof] != -1)
          r.failHere("node " + std::to_string(model.mesh.nodeLabel(node)) +
                     " is already constrained or in another rigid set");
        owner[dof] = -2;
        set.dofs.push_back(dof);
      }
      model.rigid.push_back(std::move(set));
    }
  }
}

} // namespace lamina::membrane::case_io
