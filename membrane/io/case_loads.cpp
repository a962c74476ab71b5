/// @file case_loads.cpp
/// @brief [[load]], [[point_mass]], [gravity], [[blast]] and [[drag]] of a case.

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "membrane/loads/blast_pressure.hpp"
#include "membrane/loads/drag.hpp"
#include "membrane/loads/element_pressure.hpp"
#include "membrane/loads/traction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

namespace lamina::membrane::case_io {

namespace {

/// What a [[load]] is (its `type`).
enum class LoadType { Force, Pressure, Distributed };

/// The names of `type` in a [[load]] (the one name table of LoadType).
constexpr auto kLoadTypes = core::enumNames<LoadType>({{"force", LoadType::Force},
                                                       {"pressure", LoadType::Pressure},
                                                       {"distributed", LoadType::Distributed}});

/// Where a force acts (`target`): spread over the selected elements'
/// area, or split equally over the selected nodes.
enum class ForceTarget { Elements, Nodes };

/// [[load]]: force, pressure (a follower pressure on the large-deflection
/// model) or distributed (eq. 31).
void readLoadTables(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  const int ndof = 3 * mesh.numNodes();
  const auto [xmin, xmax, ymin, ymax] = mesh.bounds();
  for (const auto& r : root.tableArray("load")) {
    Load load;
    const LoadType type = r.getChoice("type", kLoadTypes);
    load.name = r.getString("name", std::string(kLoadTypes.name(type)) +
                                        std::to_string(model.loads.size()));
    load.pattern = Eigen::VectorXd::Zero(ndof);
    switch (type) {
    case LoadType::Force: {
      const double value = r.getDouble("value");
      const Eigen::Vector3d dir = readDirection(r, Eigen::Vector3d::UnitZ());
      const ForceTarget target = r.getChoice(
          "target", {{"elements", ForceTarget::Elements}, {"nodes", ForceTarget::Nodes}},
          ForceTarget::Elements);
      const Selector sel = readSelector(r);
      if (target == ForceTarget::Elements) {
        // Total force spread uniformly over the selected area (eq. 25 with b = F/A).
        const auto elems = selectElements(mesh, sel, r);
        double area = 0;
        for (int e : elems)
          area += mesh.area(e);
        addTraction(
            mesh, elems, dir, [&](const Eigen::Vector2d&) { return value / area; }, load.pattern);
      } else {
        const auto nodes = selectNodes(mesh, sel, r);
        for (int node : nodes)
          for (int c = 0; c < 3; ++c)
            load.pattern[3 * node + c] += value * dir[c] / static_cast<double>(nodes.size());
      }
      break;
    }
    case LoadType::Pressure: {
      // The large-deflection model's follows the surface (current normal,
      // current area); the linear model's acts on the flat reference membrane.
      model.surface_loads.push_back(std::make_shared<UniformPressure>(
          load.name, mesh, selectElements(mesh, readSelectorOrAll(r), r), r.getDouble("value"),
          TimeProfile::read(r), surfaceGeometry(model.kind)));
      continue;
    }
    case LoadType::Distributed: {
      // eq. (31): b = b0 cos^2(pi r / (2 L)) for r <= L, normal to the membrane,
      // r measured from the centre; b0 is a force per volume (N/m^3) as in the paper.
      const double b0 = r.getDouble("b0");
      const double L = r.getDouble("L", std::max(xmax - xmin, ymax - ymin));
      if (!(L > 0))
        r.fail("L", "must be > 0");
      Eigen::Vector2d c(0.5 * (xmin + xmax), 0.5 * (ymin + ymax));
      if (r.has("centre"))
        c = readPoint(r, "centre");
      // times the thickness of each element's section (b is per volume)
      Eigen::VectorXd scaled = Eigen::VectorXd::Zero(ndof);
      for (int e = 0; e < mesh.numElements(); ++e) {
        const double h = model.sections[mesh.region_of[e]].thickness;
        std::vector<int> one{e};
        addTraction(
            mesh, one, Eigen::Vector3d::UnitZ(),
            [&](const Eigen::Vector2d& p) {
              const double rr = (p - c).norm();
              const double cs = std::cos(kPi * rr / (2 * L));
              return rr <= L ? h * b0 * cs * cs : 0.0;
            },
            scaled);
      }
      load.pattern = scaled;
      break;
    }
    }
    load.profile = TimeProfile::read(r);
    model.loads.push_back(std::move(load));
  }
}

/// [[point_mass]]: `mass` is the total, split equally over the selected nodes.
void readPointMasses(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  // Drag paper section 4.2: the suspended mass (one node for `at`).
  for (const auto& r : root.tableArray("point_mass")) {
    const double m = r.getDouble("mass");
    if (!(m > 0))
      r.fail("mass", "point mass must be > 0");
    const auto nodes = selectNodes(mesh, readSelector(r), r);
    for (int node : nodes)
      model.point_masses.emplace_back(node, m / double(nodes.size()));
  }
}

/// [gravity]: body force rho h g (consistent = lumped row sums) plus the point masses.
void readGravity(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  const int ndof = 3 * mesh.numNodes();
  if (auto g = root.optionalTable("gravity")) {
    const auto gv = g->getDoubleArray("g");
    if (gv.size() != 3)
      g->fail("g", "expected [gx, gy, gz] (m/s^2)");
    Load load;
    load.name = "gravity";
    load.pattern = Eigen::VectorXd::Zero(ndof);
    for (int e = 0; e < mesh.numElements(); ++e) {
      const auto& s = model.sections[mesh.region_of[e]];
      const double m3 = s.density * s.thickness * mesh.area(e) / 3;
      for (int node : mesh.triangles[e])
        for (int c = 0; c < 3; ++c)
          load.pattern[3 * node + c] += m3 * gv[c];
    }
    for (const auto& [node, m] : model.point_masses)
      for (int c = 0; c < 3; ++c)
        load.pattern[3 * node + c] += m * gv[c];
    model.loads.push_back(std::move(load));
  }
}

} // namespace

/// [[load]], [[point_mass]] and [gravity].
void readLoads(const core::TableReader& root, Model& model) {
  readLoadTables(root, model);
  readPointMasses(root, model);
  readGravity(root, model);
}

/// [[blast]]: an air blast from a charge (Kingery-Bulmash, Friedlander,
/// angle of incidence) or a user pressure history (CSV), acting on the
/// selected elements (all by default): a follower pressure on the
/// large-deflection model, along e_z on the linear model's flat membrane.
void readBlasts(const core::TableReader& root, Model& model, const std::filesystem::path& path) {
  for (const auto& r : root.tableArray("blast")) {
    const auto elems = selectElements(model.mesh, readSelectorOrAll(r), r);
    const std::string name =
        r.getString("name", "blast" + std::to_string(model.surface_loads.size()));
    if (r.has("table")) {
      if (r.has("charge"))
        r.fail("table", "give either charge (a Kingery-Bulmash blast) or table (a pressure "
                        "history), not both");
      const auto csv = path.parent_path() / r.getString("table");
      model.surface_loads.push_back(std::make_shared<BlastPressure>(
          name, elems, PressureTable::readCsv(csv.string()), surfaceGeometry(model.kind)));
      continue;
    }
    BlastCharge c;
    c.mass = r.getDouble("charge");
    if (!(c.mass > 0) || !std::isfinite(c.mass))
      r.fail("charge", "the charge must be a positive mass (kg)");
    c.tnt_equivalence = r.getDouble("tnt_equivalence", 1.0);
    if (!(c.tnt_equivalence > 0) || !std::isfinite(c.tnt_equivalence))
      r.fail("tnt_equivalence", "must be > 0");
    const auto pos = r.getDoubleArray("position");
    if (pos.size() != 3)
      r.fail("position", "expected [x, y, z] (m)");
    c.position = Eigen::Vector3d(pos[0], pos[1], pos[2]);
    c.burst = r.getChoice("burst", kBurstNames, Burst::Hemispherical);
    c.policy =
        r.getChoice("out_of_range", {{"refuse", OutOfRange::Refuse}, {"clamp", OutOfRange::Clamp}},
                    OutOfRange::Refuse);
    try {
      model.surface_loads.push_back(
          std::make_shared<BlastPressure>(name, elems, model.mesh, c, surfaceGeometry(model.kind)));
    } catch (const Error& e) {
      r.fail("charge", e.message());
    }
  }
}

/// [[drag]] (aerodynamic drag, loads/drag.hpp): on surface regions; the
/// linear model's on the reference geometry, the large-deflection model's
/// on the current one with the `area` and `normal` variants.
void readDrags(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  for (const auto& r : root.tableArray("drag")) {
    DragSpec d;
    const Selector sel = readSelectorOrAll(r);
    if (sel.kind != SelectBy::Region && sel.kind != SelectBy::All)
      r.failHere("drag acts on a surface region: give region = NAME (or nothing for all)");
    d.cd = r.getDouble("cd");
    if (!(d.cd > 0))
      r.fail("cd", "drag coefficient must be > 0");
    d.fluid_density = r.getDouble("fluid_density", 1.225);
    if (!(d.fluid_density > 0))
      r.fail("fluid_density", "must be > 0");
    d.speed = r.getChoice("velocity", kDragSpeedNames, DragSpeed::Normal);
    const bool large = model.kind == ModelKind::LargeDeflection;
    d.geometry = surfaceGeometry(model.kind);
    for (const char* key : {"area", "normal"})
      if (!large && r.has(key))
        r.fail(key, "applies to the large-deflection model only: the linear model's drag acts "
                    "on the flat reference membrane (reference areas, normal e_z)");
    d.area = r.getChoice("area", kDragAreaNames, DragArea::Current);
    d.normal = r.getChoice("normal", kDragNormalNames, DragNormal::Nodal);
    model.surface_loads.push_back(
        std::make_shared<Drag>("drag" + std::to_string(model.surface_loads.size()), mesh,
                               selectElements(mesh, sel, r), d));
  }
}

} // namespace lamina::membrane::case_io
