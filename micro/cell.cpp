#include "micro/cell.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"
#include "micro/image_io.hpp"
#include "micro/image_source.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
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

/// The axes a cell file names: "x", "y", "z" (0, 1, 2).
constexpr auto kAxisNames = core::enumNames<int>({{"x", 0}, {"y", 1}, {"z", 2}});

Eigen::Vector3d readVector3(const core::TableReader& t, const std::string& key) {
  const auto v = t.getDoubleArray(key);
  if (v.size() != 3)
    t.fail(key, "must have 3 components");
  return {v[0], v[1], v[2]};
}

/// A fiber direction or layer normal: "x", "y", "z", a vector along an axis,
/// or integers [u, v, w] (lattice direction / plane indices: periodic).
Eigen::Vector3i readLattice(const core::TableReader& t, const std::string& key) {
  const toml::node* n = t.tomlTable().get(key);
  if (n && n->is_string()) {
    if (const std::optional<int> axis = kAxisNames.parse(t.getString(key)))
      return Eigen::Vector3i::Unit(*axis);
    t.fail(key, "must be an axis (" + kAxisNames.list('"') + ") or a vector");
  }
  const Eigen::Vector3d d = readVector3(t, key);
  if (!(d.norm() > 0))
    t.fail(key, "must not be the zero vector");
  for (int i = 0; i < 3; ++i)
    if (d.cwiseAbs()[i] == d.cwiseAbs().sum())
      return Eigen::Vector3i::Unit(i);
  for (int i = 0; i < 3; ++i)
    if (d[i] != std::floor(d[i]) || std::abs(d[i]) > 16)
      t.fail(key, "an oblique direction must be integers [u, v, w] with |u| <= 16 (periodic: a "
                  "fiber runs along u Lx ex + v Ly ey + w Lz ez, a layer lies between the planes "
                  "u x/Lx + v y/Ly + w z/Lz = const)");
  return d.cast<int>();
}

/// `resolution = N` or `[N1, N2, N3]`, integers in [2, kMaxResolution]
/// (checked before any cast, so no value wraps round to a small one)
std::array<int, 3> numberList(const core::TableReader& c, const std::string& key) {
  const toml::node* res = c.tomlTable().get(key);
  const std::string range = "each count must lie in [2, " + std::to_string(kMaxResolution) + "]";
  if (!res->is_array()) {
    const auto n = static_cast<int>(c.getIntIn(key, 2, kMaxResolution));
    return {n, n, n};
  }
  const auto v = c.getDoubleArray(key);
  if (v.size() != 3)
    c.fail(key, "must be N or [N1, N2, N3]");
  std::array<int, 3> n{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (v[i] != std::floor(v[i]))
      c.fail(key, "must be integers");
    if (!(v[i] >= 2 && v[i] <= kMaxResolution))
      c.fail(key, range);
    n[i] = static_cast<int>(v[i]);
  }
  return n;
}

double positive(const core::TableReader& t, const std::string& key) {
  const double v = t.getDouble(key);
  if (!(v > 0) || !std::isfinite(v))
    t.fail(key, "must be positive");
  return v;
}

/// The keys of a yarn (docs/homogenize.md): direction (an axis), crimp (the
/// axis it undulates along, default z), width, thickness, amplitude
/// (default 0), wavelength (default the cell length along direction; must
/// divide it, so the yarn is periodic), follow_path (default true: the
/// phase's law is rotated along the centre line, yarn_orientation.hpp).
void readYarn(const core::TableReader& t, const CellSpec& cell, Inclusion& p) {
  p.width = positive(t, "width");
  p.thickness = positive(t, "thickness");
  p.setLattice(readLattice(t, "direction"));
  if (p.axis < 0)
    t.fail("direction", "a yarn runs along a cell axis: \"x\", \"y\" or \"z\"");
  p.crimp = t.getChoice("crimp", kAxisNames, p.axis == 2 ? -1 : 2);
  if (p.crimp < 0)
    t.fail("crimp", "required for a yarn along z: the axis it undulates along, \"x\" or \"y\"");
  if (p.crimp == p.axis)
    t.fail("crimp", "must differ from the yarn's direction");
  p.follow_path = t.getBool("follow_path", true);
  p.amplitude = t.getDouble("amplitude", 0.0);
  if (!(p.amplitude >= 0) || !std::isfinite(p.amplitude))
    t.fail("amplitude",
           "must not be negative (shift center along the yarn for the opposite phase)");
  const double La = cell.size[p.axis];
  p.wavelength = t.has("wavelength") ? positive(t, "wavelength") : La;
  const double periods = La / p.wavelength;
  if (!(periods >= 1) || std::abs(periods - std::round(periods)) > 1e-9 * periods)
    t.fail("wavelength", "must divide the cell length along the yarn (" + core::formatShort(La) +
                             "): the yarn must be periodic; got " + core::formatShort(periods) +
                             " periods per cell");
}

/// The keys of an inclusion's `shape` (docs/homogenize.md): radius,
/// semi_axes and orientation, direction, thickness and normal, or a yarn's.
void readShape(const core::TableReader& t, const CellSpec& cell, Inclusion& p) {
  if (!t.has("shape"))
    t.fail("shape", "required: " + kShapeNames.list('"'));
  p.shape = t.getChoice("shape", kShapeNames);
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
    p.setLattice(readLattice(t, "direction"));
    break;
  case Shape::Layer:
    p.thickness = positive(t, "thickness");
    p.setLattice(readLattice(t, "normal"));
    break;
  case Shape::Yarn:
    readYarn(t, cell, p);
    break;
  }
}

/// `lattice = [n1, n2, n3]`: positive integer counts, at most
/// kMaxInclusions copies in all.
std::array<int, 3> readLatticeCounts(const core::TableReader& t) {
  const auto c = t.getDoubleArray("lattice");
  if (c.size() != 3)
    t.fail("lattice", "must give 3 counts [n1, n2, n3]");
  std::array<int, 3> counts{};
  double copies = 1;
  for (int i = 0; i < 3; ++i) {
    const double ci = c[static_cast<std::size_t>(i)];
    if (!(ci >= 1) || ci != std::floor(ci))
      t.fail("lattice", "counts must be positive integers");
    copies *= ci;
    if (copies > static_cast<double>(kMaxInclusions))
      t.fail("lattice", "at most " + std::to_string(kMaxInclusions) +
                            " inclusions per cell (placement tests every pair)");
    counts[static_cast<std::size_t>(i)] = static_cast<int>(ci);
  }
  return counts;
}

/// The keys of a group's `placement`: center (single), lattice, or seed and
/// max_attempts (random).
void readPlacement(const core::TableReader& t, const CellSpec& cell, InclusionGroup& g) {
  Inclusion& p = g.prototype;
  g.placement = t.getChoice("placement", kPlacementNames, Placement::Single);
  switch (g.placement) {
  case Placement::Single:
    p.center = t.has("center") ? readVector3(t, "center") : Eigen::Vector3d(0.5 * cell.size);
    break;
  case Placement::Lattice:
    g.lattice = readLatticeCounts(t);
    break;
  case Placement::Random:
    if (p.shape == Shape::Yarn)
      t.fail("placement", "yarns are placed with single (center) or lattice");
    g.seed = static_cast<std::uint64_t>(t.getInt("seed", 1));
    g.max_attempts = static_cast<int>(t.getIntIn("max_attempts", 1, kMaxAttempts, 200000));
    break;
  }
}

/// The keys of how much a group places: count (random), volume_fraction,
/// min_gap; and seed refused where nothing is random.
void readAmount(const core::TableReader& t, InclusionGroup& g) {
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
}

/// One `[[inclusions]]` table (the @p index-th): its phase, shape,
/// placement and amount.
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
  readShape(t, cell, p);
  readPlacement(t, cell, g);
  readAmount(t, g);
  return g;
}

/// [cell] of an image cell: the image, its voxel_size (a scale) and a
/// resolution, if given, checked against the image's shape.
void readImageCell(const core::TableReader& c, CellSpec& cell) {
  cell.image = readImageSource(c, cell.file);
  if (c.has("voxel_size")) {
    const toml::node* v = c.tomlTable().get("voxel_size");
    cell.voxel_size = v->is_array() ? readVector3(c, "voxel_size")
                                    : Eigen::Vector3d::Constant(c.getDouble("voxel_size"));
    if (!(cell.voxel_size->minCoeff() > 0))
      c.fail("voxel_size", "voxel edge lengths must be positive");
    cell.physical_size = true; // metres, like size: the cell has a scale
  }
  const std::array<int, 3> shape = imageShape(*cell.image);
  if (c.has("resolution")) {
    const auto v = numberList(c, "resolution");
    if (std::array<int, 3>{v[0], v[1], v[2]} != shape)
      c.fail("resolution", "size mismatch: the image gives " + std::to_string(shape[0]) + " x " +
                               std::to_string(shape[1]) + " x " + std::to_string(shape[2]) +
                               " voxels (after crop and downsample); drop resolution or fix it");
  }
  cell.resolution = shape;
  if (cell.voxel_size) {
    cell.size = cell.voxel_size->cwiseProduct(Eigen::Vector3d(shape[0], shape[1], shape[2]));
    if (!(cell.size.maxCoeff() <= kMaxCellEdge))
      c.fail("voxel_size", "voxel sizes are in metres; the cell would be " +
                               core::formatShort(cell.size.maxCoeff()) + " m across (limit " +
                               core::formatShort(kMaxCellEdge) + " m)");
  }
}

/// [cell] of a generated cell: resolution (required), composite_voxels;
/// the keys of image cells refused.
void readGeneratedCell(const core::TableReader& c, CellSpec& cell) {
  std::string key;
  if (hasImageKey(c, key))
    c.fail(key, "applies to image cells (image = \"PATH\") only");
  if (!c.tomlTable().get("resolution"))
    c.fail("resolution", "required: N or [N1, N2, N3]");
  const auto v = numberList(c, "resolution");
  cell.resolution = {v[0], v[1], v[2]};
  if (c.has("composite_voxels"))
    cell.composite_voxels = c.getBool("composite_voxels", true);
}

/// [cell] size: edge lengths in metres (a scalar for a cube).
void readSize(const core::TableReader& c, CellSpec& cell) {
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

/// [[phases]]: at least one (the first is the matrix), distinct names and
/// ids (an image cell needs an id on each), at most one J sweep, not all
/// void.
void readPhases(const core::TableReader& root, const CatalogProvider& catalog, CellSpec& cell) {
  const auto phases = root.tableArray("phases");
  if (phases.empty())
    root.fail("phases", "at least one [[phases]] table is required (the first is the matrix)");
  for (const auto& t : phases) {
    Phase ph = readPhase(t, catalog);
    if (cell.phaseIndex(ph.name) >= 0)
      t.fail("name", "duplicate phase name '" + ph.name + "'");
    if (t.has("id")) {
      const auto id = t.getInt("id");
      if (id < std::numeric_limits<std::int32_t>::min() ||
          id > std::numeric_limits<std::int32_t>::max())
        t.fail("id", "must fit in 32 bits");
      ph.id = static_cast<std::int32_t>(id);
      for (const Phase& o : cell.phases)
        if (o.id == ph.id)
          t.fail("id", "phase '" + o.name + "' already owns id " + std::to_string(id));
    } else if (cell.image) {
      t.fail("id", "an image cell needs id = K on every phase: the image value it owns");
    }
    cell.phases.push_back(std::move(ph));
  }
  bool solid = false;
  for (const Phase& p : cell.phases)
    solid = solid || !p.isVoid();
  if (!solid)
    root.fail("phases", "every phase is void: a cell needs a phase with stiffness");
  int swept = 0;
  for (std::size_t i = 0; i < phases.size(); ++i)
    if (cell.phases[i].J.size() > 1 && ++swept > 1)
      phases[i].fail("J", "only one phase may carry a list of J states");
}

} // namespace

CellSpec readCellString(const std::string& text, const std::string& source,
                        const CatalogProvider& catalog,
                        const std::vector<std::string>& overrides) {
  toml::table doc = core::parseTomlString(text, source);
  for (const auto& o : overrides)
    core::applyOverride(doc, o);
  core::TableReader root(doc, source);
  CellSpec cell;
  cell.file = source;
  cell.text = text;
  cell.overrides = overrides;
  const core::TableReader c = root.table("cell");
  cell.description = c.getString("description", "");
  if (c.has("image"))
    readImageCell(c, cell);
  else
    readGeneratedCell(c, cell);
  if (c.has("size"))
    readSize(c, cell);
  readPhases(root, catalog, cell);
  const auto groups = root.tableArray("inclusions");
  if (cell.image && !groups.empty())
    groups[0].failHere("an image cell takes its voxels from the image: no [[inclusions]]");
  for (std::size_t i = 0; i < groups.size(); ++i)
    cell.groups.push_back(readGroup(groups[i], cell, i));
  root.finish();
  return cell;
}

CellSpec readCell(const std::filesystem::path& path, const CatalogProvider& catalog,
                  const std::vector<std::string>& overrides) {
  return readCellString(core::readInputFile(path), path.string(), catalog, overrides);
}

} // namespace lamina::micro
