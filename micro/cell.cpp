#include "micro/cell.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

namespace lamina::micro {

int CellSpec::phaseIndex(const std::string& name) const {
  for (std::size_t i = 0; i < phases.size(); ++i)
    if (phases[i].name == name)
      return static_cast<int>(i);
  return -1;
}

std::vector<double> CellSpec::sweepStates() const {
  for (const Phase& p : phases)
    if (!p.J.empty())
      return p.J;
  return {1.0};
}

std::vector<materials::Stiffness> CellSpec::stiffnessesAt(double J) const {
  std::vector<materials::Stiffness> out;
  for (const Phase& p : phases)
    out.push_back(p.stiffnessAt(J));
  return out;
}

std::vector<double> CellSpec::densities() const {
  std::vector<double> out;
  for (const Phase& p : phases)
    out.push_back(p.density);
  return out;
}

CatalogProvider lazyCatalog(const std::filesystem::path& path) {
  auto holder = std::make_shared<std::unique_ptr<materials::Catalog>>();
  return [holder, path]() -> const materials::Catalog& {
    if (!*holder)
      *holder = std::make_unique<materials::Catalog>(
          path.empty() ? materials::Catalog::defaultPath() : path);
    return **holder;
  };
}

namespace {

Eigen::Vector3d readVector3(const core::TableReader& t, const std::string& key) {
  const auto v = t.getDoubleArray(key);
  if (v.size() != 3)
    t.fail(key, "must have 3 components");
  return {v[0], v[1], v[2]};
}

int readAxis(const core::TableReader& t, const std::string& key) {
  const toml::node* n = t.tomlTable().get(key);
  if (n && n->is_string()) {
    const std::string w = t.getString(key);
    if (w == "x")
      return 0;
    if (w == "y")
      return 1;
    if (w == "z")
      return 2;
    t.fail(key, "must be \"x\", \"y\", \"z\" or a vector along one of them");
  }
  const Eigen::Vector3d d = readVector3(t, key);
  int axis = -1;
  for (int i = 0; i < 3; ++i)
    if (d[i] != 0) {
      if (axis >= 0)
        t.fail(key, "must lie along a coordinate axis (periodic fibers/layers)");
      axis = i;
    }
  if (axis < 0)
    t.fail(key, "must not be the zero vector");
  return axis;
}

double positive(const core::TableReader& t, const std::string& key) {
  const double v = t.getDouble(key);
  if (!(v > 0) || !std::isfinite(v))
    t.fail(key, "must be positive");
  return v;
}

InclusionGroup readGroup(const core::TableReader& t, const CellSpec& cell, std::size_t index) {
  InclusionGroup g;
  g.key = "inclusions[" + std::to_string(index) + "]";
  Inclusion& p = g.prototype;
  const std::string phase = t.getString("phase");
  p.phase = cell.phaseIndex(phase);
  if (p.phase < 0)
    t.fail("phase", "no phase named '" + phase + "'");
  if (p.phase == 0)
    t.fail("phase", "inclusions cannot be made of the matrix (the first phase)");
  const std::string shape = t.getString("shape");
  if (!parseShape(shape, p.shape))
    t.fail("shape", "unknown shape '" + shape + "' (sphere, ellipsoid, fiber, layer)");
  switch (p.shape) {
  case Shape::Sphere:
    p.semi.setConstant(positive(t, "radius"));
    break;
  case Shape::Ellipsoid: {
    p.semi = readVector3(t, "semi_axes");
    if (!(p.semi.minCoeff() > 0))
      t.fail("semi_axes", "semi-axes must be positive");
    if (auto o = t.optionalTable("orientation")) {
      const Eigen::Vector3d axis = readVector3(*o, "axis");
      if (!(axis.norm() > 0))
        o->fail("axis", "rotation axis must not be the zero vector");
      const double angle = o->getDouble("angle") * M_PI / 180.0; // degrees in files
      p.R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
    }
    break;
  }
  case Shape::Fiber:
    p.radius = positive(t, "radius");
    p.axis = readAxis(t, "direction");
    break;
  case Shape::Layer:
    p.thickness = positive(t, "thickness");
    p.axis = readAxis(t, "normal");
    break;
  }
  const std::string placement = t.getString("placement", "single");
  if (placement == "single") {
    g.placement = Placement::Single;
    p.center = t.has("center") ? readVector3(t, "center") : Eigen::Vector3d(0.5 * cell.size);
  } else if (placement == "lattice") {
    g.placement = Placement::Lattice;
    const auto c = t.getDoubleArray("lattice");
    if (c.size() != 3)
      t.fail("lattice", "must give 3 counts [n1, n2, n3]");
    double copies = 1;
    for (int i = 0; i < 3; ++i) {
      const double ci = c[static_cast<std::size_t>(i)];
      if (!(ci >= 1) || ci != std::floor(ci))
        t.fail("lattice", "counts must be positive integers");
      copies *= ci;
      if (copies > static_cast<double>(kMaxInclusions))
        t.fail("lattice", "at most " + std::to_string(kMaxInclusions) +
                              " inclusions per cell (placement tests every pair)");
      g.lattice[static_cast<std::size_t>(i)] = static_cast<int>(ci);
    }
  } else if (placement == "random") {
    g.placement = Placement::Random;
    g.seed = static_cast<std::uint64_t>(t.getInt("seed", 1));
    g.max_attempts = static_cast<int>(t.getIntIn("max_attempts", 1, kMaxAttempts, 200000));
  } else {
    t.fail("placement", "unknown placement '" + placement + "' (single, lattice, random)");
  }
  if (t.has("count")) {
    if (g.placement != Placement::Random)
      t.fail("count", "count applies to random placement (use lattice = [n1, n2, n3])");
    g.count = static_cast<int>(t.getIntIn("count", 1, kMaxInclusions));
  }
  if (t.has("volume_fraction")) {
    const double f = t.getDouble("volume_fraction");
    if (!(f > 0 && f < 1))
      t.fail("volume_fraction", "must lie in (0, 1)");
    g.volume_fraction = f;
  }
  if (g.placement == Placement::Random && g.count == 0 && !g.volume_fraction)
    t.fail("placement", "random placement needs count or volume_fraction");
  g.min_gap = t.getDouble("min_gap", 0.0);
  if (!(g.min_gap >= 0))
    t.fail("min_gap", "must not be negative");
  if (g.placement == Placement::Single && t.has("seed"))
    t.fail("seed", "seed applies to random placement");
  return g;
}

} // namespace

CellSpec readCellString(const std::string& text, const std::string& source,
                        const CatalogProvider& catalog) {
  const toml::table doc = core::parseTomlString(text, source);
  core::TableReader root(doc, source);
  CellSpec cell;
  cell.file = source;
  cell.text = text;
  const core::TableReader c = root.table("cell");
  cell.description = c.getString("description", "");
  const toml::node* res = c.tomlTable().get("resolution");
  if (!res)
    c.fail("resolution", "required: N or [N1, N2, N3]");
  if (res->is_array()) {
    const auto v = c.getDoubleArray("resolution");
    if (v.size() != 3)
      c.fail("resolution", "must be N or [N1, N2, N3]");
    for (int i = 0; i < 3; ++i) {
      const double vi = v[static_cast<std::size_t>(i)];
      if (vi != std::floor(vi))
        c.fail("resolution", "must be integers");
      if (!(vi >= 2 && vi <= kMaxResolution)) // before the cast: no overflow
        c.fail("resolution", "each count must lie in [2, " + std::to_string(kMaxResolution) + "]");
      cell.resolution[static_cast<std::size_t>(i)] = static_cast<int>(vi);
    }
  } else {
    cell.resolution.fill(static_cast<int>(c.getIntIn("resolution", 2, kMaxResolution)));
  }
  if (c.has("size")) {
    const toml::node* s = c.tomlTable().get("size");
    if (s->is_array())
      cell.size = readVector3(c, "size");
    else
      cell.size.setConstant(c.getDouble("size"));
    if (!(cell.size.minCoeff() > 0))
      c.fail("size", "edge lengths must be positive");
    if (!(cell.size.maxCoeff() <= kMaxCellEdge))
      c.fail("size", "edge lengths are in metres; " + core::formatShort(cell.size.maxCoeff()) +
                         " m is not a unit cell (limit " + core::formatShort(kMaxCellEdge) +
                         " m). Give the physical size (e.g. size = 20e-6), or leave size out "
                         "for a scale-free cell without micro-inertia");
    cell.physical_size = true;
  }
  const auto phases = root.tableArray("phases");
  if (phases.empty())
    root.fail("phases", "at least one [[phases]] table is required (the first is the matrix)");
  for (const auto& t : phases) {
    Phase ph = readPhase(t, catalog);
    if (cell.phaseIndex(ph.name) >= 0)
      t.fail("name", "duplicate phase name '" + ph.name + "'");
    cell.phases.push_back(std::move(ph));
  }
  int swept = 0;
  for (std::size_t i = 0; i < phases.size(); ++i)
    if (cell.phases[i].J.size() > 1 && ++swept > 1)
      phases[i].fail("J", "only one phase may carry a list of J states");
  const auto groups = root.tableArray("inclusions");
  for (std::size_t i = 0; i < groups.size(); ++i)
    cell.groups.push_back(readGroup(groups[i], cell, i));
  root.finish();
  return cell;
}

CellSpec readCell(const std::filesystem::path& path, const CatalogProvider& catalog) {
  return readCellString(core::readInputFile(path), path.string(), catalog);
}

} // namespace lamina::micro
