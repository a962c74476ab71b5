#include "membrane/io/case_file.hpp"

#include "materials/material_source.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/resources.hpp"
#include "core/toml_reader.hpp"
#include "materials/catalog.hpp"
#include "materials/layup.hpp"
#include "materials/library.hpp"
#include "membrane/loads/blast_pressure.hpp"
#include "membrane/loads/element_pressure.hpp"
#include "membrane/loads/follower_drag.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

namespace lamina::membrane {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Lazily opened material sources (a case with inline materials needs neither).
/// Looks a material up for the case (library, then catalog) and blames a
/// miss on the case file's key.
materials::Material lookupMaterial(materials::MaterialSource& source, const std::string& name,
                                   const core::TableReader& r, const std::string& key) {
  try {
    return source.get(name);
  } catch (const Error& e) {
    if (!e.context().file.empty())
      throw; // a broken library or catalog file: its own file and line
    r.fail(key, e.message());
  }
}

Eigen::Vector2d readPoint(const core::TableReader& r, const std::string& key) {
  const auto v = r.getDoubleArray(key);
  if (v.size() != 2)
    r.fail(key, "expected [x, y]");
  return {v[0], v[1]};
}

Eigen::Vector3d readDirection(const core::TableReader& r, const Eigen::Vector3d& fallback) {
  if (r.has("direction") && r.has("inclination_deg"))
    r.fail("direction", "give either direction or inclination_deg, not both");
  if (r.has("direction")) {
    const auto v = r.getDoubleArray("direction");
    if (v.size() != 3)
      r.fail("direction", "expected [dx, dy, dz]");
    Eigen::Vector3d d(v[0], v[1], v[2]);
    if (!(d.norm() > 0))
      r.fail("direction", "direction must be non-zero");
    return d.normalized();
  }
  if (r.has("inclination_deg")) {
    // Tilted from the normal +z towards +x (Table 2 cases 2 and 4: 30 degrees).
    const double a = r.getDouble("inclination_deg") * kPi / 180;
    return {std::sin(a), 0.0, std::cos(a)};
  }
  return fallback;
}

/// The one selector key of a table: nodes (set name), box, at, region or all.
/// What a selector key selects by.
enum class SelectBy { Nodes, Box, At, Region, All };

struct Selector {
  SelectBy kind = SelectBy::All;
  std::string name;
  std::array<double, 4> box{};
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  std::string key; // the key that selected, for errors
};

Selector readSelector(const core::TableReader& r) {
  Selector s;
  int count = 0;
  for (const char* k : {"nodes", "box", "at", "region", "all"})
    if (r.has(k))
      ++count;
  if (count != 1)
    r.failHere("give exactly one of nodes, box, at, region, all");
  if (r.has("nodes")) {
    s.kind = SelectBy::Nodes;
    s.key = "nodes";
    s.name = r.getString("nodes");
  } else if (r.has("box")) {
    s.kind = SelectBy::Box;
    s.key = "box";
    const auto v = r.getDoubleArray("box");
    if (v.size() != 4 || !(v[0] <= v[1]) || !(v[2] <= v[3]))
      r.fail("box", "expected [xmin, xmax, ymin, ymax]");
    std::copy(v.begin(), v.end(), s.box.begin());
  } else if (r.has("at")) {
    s.kind = SelectBy::At;
    s.key = "at";
    s.at = readPoint(r, "at");
  } else if (r.has("region")) {
    s.kind = SelectBy::Region;
    s.key = "region";
    s.name = r.getString("region");
  } else {
    s.kind = SelectBy::All;
    s.key = "all";
    if (!r.getBool("all", false))
      r.fail("all", "all = false selects nothing");
  }
  return s;
}

int regionIndex(const Mesh& m, const std::string& name, const core::TableReader& r,
                const std::string& key) {
  for (size_t i = 0; i < m.regions.size(); ++i)
    if (m.regions[i] == name)
      return static_cast<int>(i);
  std::string have;
  for (const auto& n : m.regions)
    have += (have.empty() ? "" : ", ") + n;
  r.fail(key, "mesh " + m.source + " has no region '" + name + "' (regions: " + have + ")");
}

/// The node nearest to @p p, which must lie on mesh @p m: within its longest
/// edge of a node (a point off the mesh is a typo, not a request for the
/// nearest boundary node).
int nodeAt(const Mesh& m, const Eigen::Vector2d& p, const core::TableReader& r,
           const std::string& key) {
  const int i = m.nearestNode(p);
  if (i < 0 || !((m.nodes[i] - p).norm() <= m.maxEdge())) {
    const auto [x0, x1, y0, y1] = m.bounds();
    r.fail(key, "point (" + core::formatShort(p.x()) + ", " + core::formatShort(p.y()) +
                    ") lies outside mesh " + m.source + " (x in [" + core::formatShort(x0) + ", " +
                    core::formatShort(x1) + "], y in [" + core::formatShort(y0) + ", " +
                    core::formatShort(y1) + "])");
  }
  return i;
}

bool inBox(const Eigen::Vector2d& p, const std::array<double, 4>& b, double tol) {
  return p.x() >= b[0] - tol && p.x() <= b[1] + tol && p.y() >= b[2] - tol && p.y() <= b[3] + tol;
}

std::vector<int> selectNodes(const Mesh& m, const Selector& s, const core::TableReader& r) {
  std::vector<int> out;
  const double tol = 1e-9 * m.maxEdge();
  if (s.kind == SelectBy::Nodes) {
    auto it = m.node_sets.find(s.name);
    if (it == m.node_sets.end()) {
      std::string have;
      for (const auto& [n, v] : m.node_sets)
        have += (have.empty() ? "" : ", ") + n;
      r.fail("nodes",
             "mesh " + m.source + " has no node set '" + s.name + "' (sets: " + have + ")");
    }
    out = it->second;
  } else if (s.kind == SelectBy::Box) {
    for (int i = 0; i < m.numNodes(); ++i)
      if (inBox(m.nodes[i], s.box, tol))
        out.push_back(i);
  } else if (s.kind == SelectBy::At) {
    out.push_back(nodeAt(m, s.at, r, "at"));
  } else if (s.kind == SelectBy::Region) {
    const int reg = regionIndex(m, s.name, r, "region");
    std::set<int> nodes;
    for (int e = 0; e < m.numElements(); ++e)
      if (m.region_of[e] == reg)
        nodes.insert(m.triangles[e].begin(), m.triangles[e].end());
    out.assign(nodes.begin(), nodes.end());
  } else {
    for (int i = 0; i < m.numNodes(); ++i)
      out.push_back(i);
  }
  if (out.empty())
    r.fail(s.key, "selects no node of mesh " + m.source);
  return out;
}

std::vector<int> selectElements(const Mesh& m, const Selector& s, const core::TableReader& r) {
  std::vector<int> out;
  const double tol = 1e-9 * m.maxEdge();
  if (s.kind == SelectBy::Nodes) {
    r.fail("nodes", "this load acts on elements: select them with box, at, region or all");
  } else if (s.kind == SelectBy::Box) {
    for (int e = 0; e < m.numElements(); ++e)
      if (inBox(m.centroid(e), s.box, tol))
        out.push_back(e);
  } else if (s.kind == SelectBy::At) {
    // The triangle containing the point (barycentric test).
    for (int e = 0; e < m.numElements() && out.empty(); ++e) {
      const auto& t = m.triangles[e];
      const Eigen::Vector2d a = m.nodes[t[0]], b = m.nodes[t[1]], c = m.nodes[t[2]];
      auto cross = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
        return p.x() * q.y() - p.y() * q.x();
      };
      const double A2 = cross(b - a, c - a), eps = -1e-12 * A2;
      if (cross(b - a, s.at - a) >= eps && cross(c - b, s.at - b) >= eps &&
          cross(a - c, s.at - c) >= eps)
        out.push_back(e);
    }
  } else if (s.kind == SelectBy::Region) {
    const int reg = regionIndex(m, s.name, r, "region");
    for (int e = 0; e < m.numElements(); ++e)
      if (m.region_of[e] == reg)
        out.push_back(e);
  } else {
    for (int e = 0; e < m.numElements(); ++e)
      out.push_back(e);
  }
  if (out.empty())
    r.fail(s.key, "selects no element of mesh " + m.source);
  return out;
}

Mesh readMesh(const core::TableReader& r, const std::filesystem::path& case_path) {
  const std::string type = r.getString("type", "rectangle");
  if (type == "rectangle") {
    const double Lx = r.getDouble("Lx");
    const double Ly = r.getDouble("Ly", Lx);
    const auto nx = r.getInt("nx");
    const auto ny = r.getInt("ny", nx);
    if (!(Lx > 0))
      r.fail("Lx", "must be > 0");
    if (!(Ly > 0))
      r.fail("Ly", "must be > 0");
    if (nx < 1 || nx > 100000)
      r.fail("nx", "must be in [1, 100000]");
    if (ny < 1 || ny > 100000)
      r.fail("ny", "must be in [1, 100000]");
    requireRunMemory(double(nx + 1) * double(ny + 1),
                     "a " + std::to_string(nx) + " x " + std::to_string(ny) + " rectangle",
                     {r.file(), 0, r.path("nx")});
    return structuredRectangle(Lx, Ly, static_cast<int>(nx), static_cast<int>(ny));
  }
  if (type == "gmsh") {
    std::filesystem::path file = r.getString("file");
    if (file.is_relative())
      file = case_path.parent_path() / file;
    if (!std::filesystem::exists(file))
      r.fail("file", "mesh file not found: " + file.string());
    return readGmsh(file);
  }
  r.fail("type", "unknown mesh type '" + type + "' (rectangle, gmsh)");
}

/// Micro-inertia keys of a section: an inline `dispersion` (zeta^2 D, 6x6,
/// kg/m) for inline materials, and `micro_inertia = false` to drop the
/// material's (on by default).
void readMicroInertia(const core::TableReader& r, bool named, Section& s) {
  if (r.has("dispersion")) {
    if (named)
      r.fail("dispersion", "only with an inline material (E or C): a named material brings its "
                           "own dispersion from the library");
    const auto d = r.getMatrix("dispersion");
    bool ok = d.size() == 6;
    for (const auto& row : d)
      ok = ok && row.size() == 6;
    if (!ok)
      r.fail("dispersion", "expected 6 rows of 6 (zeta^2 D, kg/m, lamina order)");
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        s.dispersion(i, j) = d[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    try {
      materials::validateDispersion(s.dispersion, "section");
    } catch (const Error& e) {
      r.fail("dispersion", e.message());
    }
  }
  if (!r.getBool("micro_inertia", true))
    s.dispersion.setZero();
}

/// Reads one [[section]]: material by name, inline isotropic/anisotropic, or plies.
/// The large-deflection keys of a [[section]] (material axis, pre-stress,
/// tension_only, failure thresholds); an error under the linear model.
void readFabricKeys(const core::TableReader& r, ModelKind kind, Section& s) {
  for (const char* key :
       {"material_axis", "prestress", "tension_only", "failure_strain", "failure_stress"})
    if (kind == ModelKind::Linear && r.has(key))
      r.fail(key, "needs model = \"large_deflection\"");
  if (kind == ModelKind::Linear)
    return;
  if (r.has("material_axis")) {
    const auto v = r.getDoubleArray("material_axis");
    if (v.size() != 3 || !(Eigen::Vector3d(v[0], v[1], v[2]).norm() > 0))
      r.fail("material_axis", "expected a non-zero [ax, ay, az]");
    s.axis = Eigen::Vector3d(v[0], v[1], v[2]).normalized();
  }
  if (r.has("prestress")) {
    const toml::node* node = r.raw("prestress");
    if (node->is_array()) {
      const auto v = r.getDoubleArray("prestress");
      if (v.size() != 3)
        r.fail("prestress", "expected a tension T (N/m) or [T11, T22, T12] (N/m)");
      s.prestress = {v[0], v[1], v[2]};
    } else {
      const double T = r.getDouble("prestress");
      s.prestress = {T, T, 0.0};
    }
    if (!s.prestress.allFinite())
      r.fail("prestress", "must be finite");
  }
  s.tension_only = r.getBool("tension_only", false);
  s.failure_strain = r.getDouble("failure_strain", s.failure_strain);
  s.failure_stress = r.getDouble("failure_stress", s.failure_stress);
  if (!(s.failure_strain > 0))
    r.fail("failure_strain", "must be > 0");
  if (!(s.failure_stress > 0))
    r.fail("failure_stress", "must be > 0");
}

Section readSection(const core::TableReader& r, materials::MaterialSource& res, ModelKind kind) {
  Section s;
  std::optional<double> default_thickness;
  const bool by_name = r.has("material"), iso = r.has("E"), aniso = r.has("C"),
             layup = r.has("plies");
  if (by_name + iso + aniso + layup != 1)
    r.failHere("give exactly one of material, E (with nu, density), C (with density), plies");
  if (by_name) {
    s.material = r.getString("material");
    const auto m = lookupMaterial(res, s.material, r, "material");
    s.D = m.C.matrix();
    s.density = m.density;
    if (m.dispersion)
      s.dispersion = *m.dispersion;
    default_thickness = m.thickness;
  } else if (iso) {
    const double E = r.getDouble("E"), nu = r.getDouble("nu");
    if (!(E > 0))
      r.fail("E", "must be > 0");
    if (!(nu > -1 && nu < 0.5))
      r.fail("nu", "must be in (-1, 0.5)");
    s.D = materials::Stiffness::isotropic(E, nu).matrix();
    s.density = r.getDouble("density");
    s.material = "isotropic E=" + std::to_string(E) + " nu=" + std::to_string(nu);
  } else if (aniso) {
    s.D = materials::readMatrix6(r, "C");
    s.density = r.getDouble("density");
    s.material = "inline C";
  } else {
    const auto texts = r.getStringArray("plies");
    std::vector<materials::Ply> plies;
    for (const auto& t : texts) {
      try {
        plies.push_back(materials::parsePly(t));
      } catch (const Error& e) {
        r.fail("plies", e.message());
      }
    }
    materials::Material m;
    try {
      m = materials::makeLayup("case-layup", plies, [&](const std::string& n) {
        return lookupMaterial(res, n, r, "plies");
      });
    } catch (const Error& e) {
      if (!e.context().file.empty())
        throw;
      r.fail("plies", e.message());
    }
    s.D = m.C.matrix();
    s.density = m.density;
    if (m.dispersion)
      s.dispersion = *m.dispersion;
    default_thickness = m.thickness;
    s.material = "layup of " + std::to_string(plies.size()) + " plies";
  }
  readMicroInertia(r, by_name || layup, s);
  if (kind == ModelKind::LargeDeflection && s.hasMicroInertia())
    r.failHere("the material has micro-inertia (a dispersion), which only the linear model "
               "carries: set micro_inertia = false for the large-deflection model");
  if (r.has("thickness") || !default_thickness) {
    s.thickness = r.getDouble("thickness");
    if (!(s.thickness > 0))
      r.fail("thickness", "thickness must be > 0");
  } else {
    s.thickness = *default_thickness;
  }
  if (!(s.density > 0) || !std::isfinite(s.density))
    r.failHere("density must be finite and > 0");
  try {
    materials::Stiffness(s.D).validate(s.material);
  } catch (const Error& e) {
    r.failHere(e.message());
  }
  readFabricKeys(r, kind, s);
  return s;
}

/// Consistent nodal forces of a traction b(x, y) (N/m^2) on the elements,
/// integrated with the 3-point edge-midpoint rule (exact for quadratics).
template <typename F>
void addTraction(const Mesh& m, const std::vector<int>& elems, const Eigen::Vector3d& dir,
                 F&& traction, Eigen::VectorXd& f) {
  for (int e : elems) {
    const auto& t = m.triangles[e];
    const double A = m.area(e);
    for (int q = 0; q < 3; ++q) {
      // Midpoint of edge (q, q+1): N_q = N_{q+1} = 1/2, the third is 0.
      const Eigen::Vector2d p = 0.5 * (m.nodes[t[q]] + m.nodes[t[(q + 1) % 3]]);
      const double w = A / 3 * traction(p);
      for (int k : {q, (q + 1) % 3})
        for (int c = 0; c < 3; ++c)
          f[3 * t[k] + c] += 0.5 * w * dir[c];
    }
  }
}

/// [[section]]: one per region; a section without `region` covers every region left.
void readSections(const core::TableReader& root, const MaterialSources& sources, Model& model) {
  const Mesh& mesh = model.mesh;
  materials::MaterialSource resolver(sources.library_path, sources.catalog_path);
  model.sections.assign(mesh.regions.size(), Section{});
  std::vector<bool> assigned(mesh.regions.size(), false);
  const auto sections = root.tableArray("section");
  if (sections.empty())
    root.fail("section", "at least one [[section]] is required");
  for (const auto& sr : sections) {
    const Section s = readSection(sr, resolver, model.kind);
    if (sr.has("region")) {
      const int reg = regionIndex(mesh, sr.getString("region"), sr, "region");
      if (assigned[reg])
        sr.fail("region", "region '" + mesh.regions[reg] + "' assigned twice");
      model.sections[reg] = s;
      model.sections[reg].name = mesh.regions[reg];
      assigned[reg] = true;
    } else {
      for (size_t g = 0; g < assigned.size(); ++g)
        if (!assigned[g]) {
          model.sections[g] = s;
          model.sections[g].name = mesh.regions[g];
          assigned[g] = true;
        }
    }
  }
  for (size_t g = 0; g < assigned.size(); ++g)
    if (!assigned[g])
      root.fail("section", "mesh region '" + mesh.regions[g] + "' has no section");
}

/// [time], [solver] and [output].
void readTimeAndOutput(const core::TableReader& root, Model& model) {
  {
    const auto t = root.table("time");
    auto& ts = model.time;
    ts.integrator =
        t.getChoice("integrator",
                    {{"newmark", IntegratorKind::Newmark}, {"explicit", IntegratorKind::Explicit}},
                    model.kind == ModelKind::LargeDeflection ? IntegratorKind::Explicit
                                                             : IntegratorKind::Newmark);
    if (ts.integrator == IntegratorKind::Newmark && model.kind == ModelKind::LargeDeflection)
      t.fail("integrator", "the large-deflection model needs integrator = \"explicit\"");
    // Row sums of M_D vanish (B of a translation is 0): lumping would drop it.
    for (size_t k = 0; k < model.sections.size(); ++k)
      if (ts.integrator == IntegratorKind::Explicit && model.sections[k].hasMicroInertia())
        t.fail("integrator", "section[" + std::to_string(k) +
                                 "] has micro-inertia (a dispersion), which needs the Newmark "
                                 "scheme (its gradient mass cannot be lumped): use integrator = "
                                 "\"newmark\" or micro_inertia = false in the section");
    const bool expl = ts.integrator == IntegratorKind::Explicit;
    for (const char* key : {"safety", "damping"})
      if (!expl && t.has(key))
        t.fail(key, "needs integrator = \"explicit\"");
    ts.safety = t.getDouble("safety", ts.safety);
    if (!(ts.safety > 0 && ts.safety <= 1))
      t.fail("safety", "safety factor must be in (0, 1]");
    ts.damping = t.getDouble("damping", 0.0);
    if (!(ts.damping >= 0) || !std::isfinite(ts.damping))
      t.fail("damping", "damping must be >= 0 (1/s)");
    // Explicit: dt optional (0 = safety x stable step).
    ts.dt = expl ? t.getDouble("dt", 0.0) : t.getDouble("dt");
    if ((!expl || t.has("dt")) && (!(ts.dt > 0) || !std::isfinite(ts.dt)))
      t.fail("dt", "time step dt must be > 0");
    ts.t_end = t.getDouble("t_end");
    if (!(ts.t_end > 0))
      t.fail("t_end", "t_end must be > 0");
    // The run takes round(t_end / dt) steps: at least one, and a bounded
    // number (an explicit run without dt is checked once its step is known).
    const double steps = ts.dt > 0 ? std::round(ts.t_end / ts.dt) : 1.0;
    if (!(steps >= 1))
      t.fail("t_end", "t_end = " + core::formatShort(ts.t_end) + " s is less than half of dt = " +
                          core::formatShort(ts.dt) + " s: the run would take no step");
    if (!(steps <= kMaxSteps))
      t.fail("dt", "t_end / dt = " + core::formatShort(steps) + " steps; at most " +
                       core::formatShort(kMaxSteps) + " (raise dt or lower t_end)");
    ts.beta1 = t.getDouble("beta1", 0.5);
    ts.beta2 = t.getDouble("beta2", 0.5);
    if (ts.beta1 < 0 || ts.beta1 > 1)
      t.fail("beta1", "must be in [0, 1]");
    if (ts.beta2 < 0 || ts.beta2 > 1)
      t.fail("beta2", "must be in [0, 1]");
    ts.hht_alpha = t.getDouble("hht_alpha", 0.0);
    if (ts.hht_alpha < -1.0 / 3 || ts.hht_alpha > 0)
      t.fail("hht_alpha", "HHT alpha must be in [-1/3, 0]");
    if (ts.hht_alpha != 0 && (t.has("beta1") || t.has("beta2")))
      t.fail("hht_alpha", "with hht_alpha, beta1 and beta2 follow from alpha: do not give them");
    if (ts.hht_alpha != 0) {
      ts.beta1 = 0.5 - ts.hht_alpha;
      ts.beta2 = 0.5 * (1 - ts.hht_alpha) * (1 - ts.hht_alpha);
    }
    ts.lumped = t.getChoice("mass", {{"consistent", false}, {"lumped", true}}, false);
  }
  if (auto s = root.optionalTable("solver")) {
    auto& ts = model.time;
    ts.solver = s->getChoice(
        "type", {{"cg", LinearSolverKind::Cg}, {"cholesky", LinearSolverKind::Cholesky}},
        LinearSolverKind::Cg);
    ts.tolerance = s->getDouble("tolerance", ts.tolerance);
    if (!(ts.tolerance > 0 && ts.tolerance < 1))
      s->fail("tolerance", "must be in (0, 1)");
    ts.max_iterations = static_cast<int>(s->getInt("max_iterations", ts.max_iterations));
    if (ts.max_iterations < 1)
      s->fail("max_iterations", "must be >= 1");
    ts.projection = static_cast<int>(s->getInt("projection", ts.projection));
    if (ts.projection < 0 || ts.projection > 100)
      s->fail("projection", "must be in [0, 100]");
    ts.drag_iterations = static_cast<int>(s->getInt("drag_iterations", ts.drag_iterations));
    if (ts.drag_iterations < 1)
      s->fail("drag_iterations", "must be >= 1");
    ts.drag_tolerance = s->getDouble("drag_tolerance", ts.drag_tolerance);
  }
  if (auto o = root.optionalTable("output")) {
    model.output.field_every = static_cast<int>(o->getInt("field_every", 10));
    model.output.energy_every = static_cast<int>(o->getInt("energy_every", 1));
    model.output.fields = o->getBool("fields", true);
    model.output.checkpoint_every = o->getInt("checkpoint_every", 0);
    if (model.output.checkpoint_every < 0)
      o->fail("checkpoint_every", "must be >= 0 (0: a checkpoint only on SIGINT/SIGTERM)");
    if (model.output.field_every < 0)
      o->fail("field_every", "must be >= 0");
    if (model.output.energy_every < 1)
      o->fail("energy_every", "must be >= 1");
  }
}

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
          r.failHere("node " + std::to_string(node) + " is already constrained by '" +
                     model.constraints[owner[dof]].name + "'");
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

/// [[load]], [[point_mass]] and [gravity].
void readLoads(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  const int ndof = 3 * mesh.numNodes();
  const auto [xmin, xmax, ymin, ymax] = mesh.bounds();
  for (const auto& r : root.tableArray("load")) {
    Load load;
    const std::string type = r.getString("type");
    load.name = r.getString("name", type + std::to_string(model.loads.size()));
    load.pattern = Eigen::VectorXd::Zero(ndof);
    if (type == "force") {
      const double value = r.getDouble("value");
      const Eigen::Vector3d dir = readDirection(r, Eigen::Vector3d::UnitZ());
      const std::string target = r.getString("target", "elements");
      const Selector sel = readSelector(r);
      if (target == "elements") {
        // Total force spread uniformly over the selected area (eq. 25 with b = F/A).
        const auto elems = selectElements(mesh, sel, r);
        double area = 0;
        for (int e : elems)
          area += mesh.area(e);
        addTraction(
            mesh, elems, dir, [&](const Eigen::Vector2d&) { return value / area; }, load.pattern);
      } else if (target == "nodes") {
        const auto nodes = selectNodes(mesh, sel, r);
        for (int node : nodes)
          for (int c = 0; c < 3; ++c)
            load.pattern[3 * node + c] += value * dir[c] / static_cast<double>(nodes.size());
      } else {
        r.fail("target", "target must be \"elements\" or \"nodes\"");
      }
    } else if (type == "pressure") {
      const double p = r.getDouble("value");
      const auto elems =
          r.has("nodes") || r.has("box") || r.has("at") || r.has("region") || r.has("all")
              ? selectElements(mesh, readSelector(r), r)
              : selectElements(mesh, Selector{SelectBy::All, "", {}, {}, "all"}, r);
      if (model.kind == ModelKind::LargeDeflection) {
        // Follows the surface: current normal, current area.
        model.surface_loads.push_back(
            std::make_shared<UniformPressure>(load.name, elems, p, TimeProfile::read(r)));
        continue;
      }
      addTraction(
          mesh, elems, Eigen::Vector3d::UnitZ(), [&](const Eigen::Vector2d&) { return p; },
          load.pattern);
    } else if (type == "distributed") {
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
    } else {
      r.fail("type", "unknown load type '" + type + "' (force, pressure, distributed)");
    }
    load.profile = TimeProfile::read(r);
    model.loads.push_back(std::move(load));
  }

  // Point masses (drag paper section 4.2: the suspended mass).
  // `mass` is the total, split equally over the selected nodes (one node for `at`).
  for (const auto& r : root.tableArray("point_mass")) {
    const double m = r.getDouble("mass");
    if (!(m > 0))
      r.fail("mass", "point mass must be > 0");
    const auto nodes = selectNodes(mesh, readSelector(r), r);
    for (int node : nodes)
      model.point_masses.emplace_back(node, m / double(nodes.size()));
  }

  // Gravity: body force rho h g (consistent = lumped row sums) plus the point masses.
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

/// [[drag]] (issue 5): on surface regions.
/// [[blast]]: an air blast from a charge (Kingery-Bulmash, Friedlander,
/// angle of incidence) or a user pressure history (CSV), acting as a
/// follower pressure on the selected elements (all by default).
void readBlasts(const core::TableReader& root, Model& model, const std::filesystem::path& path) {
  for (const auto& r : root.tableArray("blast")) {
    if (model.kind != ModelKind::LargeDeflection)
      r.failHere("[[blast]] needs model = \"large_deflection\" (a follower load)");
    const bool selected =
        r.has("nodes") || r.has("box") || r.has("at") || r.has("region") || r.has("all");
    const auto elems = selectElements(
        model.mesh, selected ? readSelector(r) : Selector{SelectBy::All, "", {}, {}, "all"}, r);
    const std::string name =
        r.getString("name", "blast" + std::to_string(model.surface_loads.size()));
    if (r.has("table")) {
      if (r.has("charge"))
        r.fail("table", "give either charge (a Kingery-Bulmash blast) or table (a pressure "
                        "history), not both");
      const auto csv = path.parent_path() / r.getString("table");
      model.surface_loads.push_back(
          std::make_shared<BlastPressure>(name, elems, PressureTable::readCsv(csv.string())));
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
    c.burst = r.getChoice("burst", burstChoices(), Burst::Hemispherical);
    c.policy =
        r.getChoice("out_of_range", {{"refuse", OutOfRange::Refuse}, {"clamp", OutOfRange::Clamp}},
                    OutOfRange::Refuse);
    try {
      model.surface_loads.push_back(std::make_shared<BlastPressure>(name, elems, model.mesh, c));
    } catch (const Error& e) {
      r.fail("charge", e.message());
    }
  }
}

void readDrags(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  const int n = mesh.numNodes();
  for (const auto& r : root.tableArray("drag")) {
    Drag d;
    const Selector sel =
        r.has("region") ? readSelector(r) : Selector{SelectBy::All, "", {}, {}, "all"};
    if (sel.kind != SelectBy::Region && sel.kind != SelectBy::All)
      r.failHere("drag acts on a surface region: give region = NAME (or nothing for all)");
    d.cd = r.getDouble("cd");
    if (!(d.cd > 0))
      r.fail("cd", "drag coefficient must be > 0");
    d.fluid_density = r.getDouble("fluid_density", 1.225);
    if (!(d.fluid_density > 0))
      r.fail("fluid_density", "must be > 0");
    d.resultant = r.getChoice("velocity", {{"normal", false}, {"resultant", true}}, false);
    const auto elems = selectElements(mesh, sel, r);
    if (model.kind == ModelKind::LargeDeflection) {
      model.surface_loads.push_back(
          std::make_shared<FollowerDrag>("drag" + std::to_string(model.surface_loads.size()), elems,
                                         d.cd, d.fluid_density, d.resultant));
      continue;
    }
    std::vector<double> area(n, 0.0);
    for (int e : elems)
      for (int node : mesh.triangles[e])
        area[node] += mesh.area(e) / 3;
    for (int i = 0; i < n; ++i)
      if (area[i] > 0) {
        d.nodes.push_back(i);
        d.area.push_back(area[i]);
      }
    model.drags.push_back(std::move(d));
  }
}

/// [initial]: uniform initial velocity (optional).
void readInitial(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  const int n = mesh.numNodes();
  const int ndof = 3 * n;
  if (auto ini = root.optionalTable("initial")) {
    model.v0 = Eigen::VectorXd::Zero(ndof);
    if (ini->has("velocity") || !ini->has("mode")) {
      const auto v = ini->getDoubleArray("velocity");
      if (v.size() != 3)
        ini->fail("velocity", "expected [vx, vy, vz]");
      for (int i = 0; i < n; ++i)
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
      for (int i = 0; i < n; ++i)
        model.v0[3 * i + 2] += V *
                               std::sin(mn[0] * kPi * (mesh.nodes[i].x() - xmin) / (xmax - xmin)) *
                               std::sin(mn[1] * kPi * (mesh.nodes[i].y() - ymin) / (ymax - ymin));
    } else if (ini->has("mode_velocity")) {
      ini->fail("mode_velocity", "needs mode = [m, n]");
    }
  }
}

/// Top-level `model`: "linear" (default) or "large_deflection".
ModelKind readModelKind(const core::TableReader& root) {
  return root.getChoice(
      "model", {{"linear", ModelKind::Linear}, {"large_deflection", ModelKind::LargeDeflection}},
      ModelKind::Linear);
}

/// Parses `components` (a subset of "xyz") into component indices.
std::vector<int> readComponents(const core::TableReader& r) {
  const std::string comps = r.getString("components", "xyz");
  std::vector<int> out;
  for (char ch : comps) {
    const auto k = std::string("xyz").find(ch);
    if (k == std::string::npos || std::count(comps.begin(), comps.end(), ch) > 1)
      r.fail("components", "components is a subset of \"xyz\"");
    out.push_back(static_cast<int>(k));
  }
  if (out.empty())
    r.fail("components", "components is a subset of \"xyz\"");
  return out;
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
          r.failHere("node " + std::to_string(node) +
                     " is already constrained or in another rigid set");
        owner[dof] = -2;
        set.dofs.push_back(dof);
      }
      model.rigid.push_back(std::move(set));
    }
  }
}

/// Features only the explicit integrator has.
void checkIntegrator(const core::TableReader& root, const Model& model) {
  if (model.time.integrator == IntegratorKind::Explicit)
    return;
  if (!model.springs.empty())
    root.fail("spring", "springs need time.integrator = \"explicit\"");
  if (!model.rigid.empty())
    root.fail("rigid", "rigid sets need time.integrator = \"explicit\"");
}

/// [[probe]].
void readProbes(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  std::set<std::string> names;
  for (const auto& r : root.tableArray("probe")) {
    Probe p;
    p.name = r.getString("name");
    if (const std::string why = core::nameProblem(p.name); !why.empty())
      r.fail("name", "probe name " + why); // names a CSV column
    if (!names.insert(p.name).second)
      r.fail("name", "duplicate probe '" + p.name + "'");
    p.node = nodeAt(mesh, readPoint(r, "at"), r, "at");
    model.probes.push_back(p);
  }
}

} // namespace

toml::table loadCaseDocument(const std::filesystem::path& path,
                             const std::vector<std::string>& overrides) {
  if (!std::filesystem::exists(path))
    throw Error("case file not found", ErrorContext{path.string(), 0, ""});
  toml::table doc = core::parseTomlFile(path);
  for (const auto& o : overrides)
    core::applyOverride(doc, o);
  return doc;
}

Model buildModel(const toml::table& doc, const std::filesystem::path& path,
                 const MaterialSources& sources) {
  core::TableReader root(doc, path.string());
  Model model;
  model.name = root.getString("name", path.stem().string());
  // The name becomes <name>.h5 and <name>.xdmf in the output folder.
  if (const std::string why = core::nameProblem(model.name); !why.empty())
    root.fail("name", "case name '" + model.name + "' " + why +
                          (root.has("name") ? "" : " (it is the file's stem: set name = ...)"));
  (void)root.getString("description", "");
  model.compare_without_drag = root.getBool("compare_without_drag", false);
  model.kind = readModelKind(root);
  model.mesh = readMesh(root.table("mesh"), path);
  if (model.kind == ModelKind::Linear && !model.mesh.flat())
    root.table("mesh").fail("file", "mesh " + model.mesh.source +
                                        " is not flat (z != 0): the linear model needs a mesh "
                                        "in the z = 0 plane; use model = \"large_deflection\"");
  readSections(root, sources, model);
  readTimeAndOutput(root, model);
  std::vector<int> owner = readConstraints(root, model);
  readLoads(root, model);
  readBlasts(root, model, path);
  readDrags(root, model);
  if (model.compare_without_drag && model.drags.empty() && model.surface_loads.empty())
    root.fail("compare_without_drag", "needs at least one [[drag]] table");
  readSprings(root, model);
  readRigidSets(root, model, owner);
  readInitial(root, model);
  readProbes(root, model);
  checkIntegrator(root, model);
  root.finish();
  return model;
}

Model readCase(const std::filesystem::path& path, const std::vector<std::string>& overrides,
               const MaterialSources& sources) {
  return buildModel(loadCaseDocument(path, overrides), path, sources);
}

} // namespace lamina::membrane
