#include "membrane/model/mesh.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/resources.hpp"
#include "membrane/io/msh_check.hpp"

#include <gmsh.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>
#include <mutex>
#include <unordered_map>

namespace lamina::membrane {

double Mesh::area(int e) const {
  const auto& t = triangles[e];
  const Eigen::Vector2d a = nodes[t[1]] - nodes[t[0]], b = nodes[t[2]] - nodes[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

double Mesh::area3(int e) const {
  const auto& t = triangles[e];
  return 0.5 * (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0])).norm();
}

Eigen::Vector2d Mesh::centroid(int e) const {
  const auto& t = triangles[e];
  return (nodes[t[0]] + nodes[t[1]] + nodes[t[2]]) / 3.0;
}

int Mesh::nearestNode(const Eigen::Vector2d& p) const {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < numNodes(); ++i) {
    const double di = (nodes[i] - p).squaredNorm();
    if (di < d * (1 - 1e-12)) { // ties (symmetric grids) go to the lowest index
      d = di;
      best = i;
    }
  }
  return best;
}

std::array<double, 4> Mesh::bounds() const {
  std::array<double, 4> b{
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& p : nodes) {
    b[0] = std::min(b[0], p.x());
    b[1] = std::max(b[1], p.x());
    b[2] = std::min(b[2], p.y());
    b[3] = std::max(b[3], p.y());
  }
  return b;
}

double Mesh::maxEdge() const {
  double h = 0;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k)
      h = std::max(h, (nodes[t[k]] - nodes[t[(k + 1) % 3]]).norm());
  return h;
}

void requireRunMemory(double nodes, const std::string& what, const ErrorContext& context) {
  if (!(nodes <= kMaxNodes))
    throw Error(what + " has " + core::formatShort(nodes) + " nodes; at most " +
                    core::formatShort(kMaxNodes),
                context);
  core::requireMemory(nodes * kRunBytesPerNode,
                      "a run on " + what + " (" + core::formatShort(nodes) + " nodes)", context);
}

void finalizeMesh(Mesh& mesh) {
  LAMINA_CHECK(!mesh.triangles.empty(), mesh.source, ": mesh has no triangles");
  LAMINA_CHECK(mesh.region_of.size() == mesh.triangles.size(), mesh.source,
               ": region list does not match the triangles");
  const int n = mesh.numNodes();
  LAMINA_CHECK(mesh.z.empty() || static_cast<int>(mesh.z.size()) == n, mesh.source,
               ": z list does not match the nodes");
  if (std::all_of(mesh.z.begin(), mesh.z.end(), [](double v) { return v == 0.0; }))
    mesh.z.clear();
  for (int e = 0; e < mesh.numElements(); ++e) {
    auto& t = mesh.triangles[e];
    for (int k = 0; k < 3; ++k)
      LAMINA_CHECK(t[k] >= 0 && t[k] < n, mesh.source, ": triangle ", e,
                   " refers to a missing node");
    LAMINA_CHECK(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], mesh.source, ": triangle ", e,
                 " repeats a node");
    if (mesh.flat() && mesh.area(e) < 0)
      std::swap(t[1], t[2]);
    // Degenerate: area tiny compared with the square of its longest edge.
    double l2 = 0;
    for (int k = 0; k < 3; ++k)
      l2 = std::max(l2, (mesh.point(t[k]) - mesh.point(t[(k + 1) % 3])).squaredNorm());
    LAMINA_CHECK((mesh.flat() ? mesh.area(e) : mesh.area3(e)) > 1e-12 * l2, mesh.source,
                 ": triangle ", e, " is degenerate (zero area)");
  }
  for (auto& [name, set] : mesh.node_sets) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
}

Mesh structuredRectangle(double Lx, double Ly, int nx, int ny) {
  LAMINA_CHECK(Lx > 0 && Ly > 0, "structured mesh: lengths must be positive");
  LAMINA_CHECK(nx >= 1 && ny >= 1, "structured mesh: nx and ny must be >= 1");
  Mesh m;
  m.source = "structured";
  const int nxp = nx + 1;
  m.nodes.reserve(static_cast<size_t>(nxp) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      m.nodes.emplace_back(Lx * i / nx, Ly * j / ny);
  auto id = [nxp](int i, int j) { return j * nxp + i; };
  m.triangles.reserve(2 * static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // Square split by the diagonal (i,j)-(i+1,j+1), as in the paper's grid.
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.region_of.assign(m.triangles.size(), 0);
  m.regions = {"all"};
  auto& left = m.node_sets["left"];
  auto& right = m.node_sets["right"];
  auto& bottom = m.node_sets["bottom"];
  auto& top = m.node_sets["top"];
  for (int j = 0; j <= ny; ++j) {
    left.push_back(id(0, j));
    right.push_back(id(nx, j));
  }
  for (int i = 0; i <= nx; ++i) {
    bottom.push_back(id(i, 0));
    top.push_back(id(i, ny));
  }
  auto& edges = m.node_sets["edges"];
  for (const auto* s : {&left, &right, &bottom, &top})
    edges.insert(edges.end(), s->begin(), s->end());
  finalizeMesh(m);
  return m;
}

namespace {
/// gmsh keeps global state: one reader at a time.
std::mutex gmsh_mutex;

/// Nodes the surfaces of the open gmsh model will get, from its meshed
/// curves: with the mean boundary edge h and the surface area A, a mesh of
/// near-equilateral triangles has about A / (sqrt(3)/4 h^2) triangles and
/// half as many nodes.
double estimateSurfaceNodes() {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> etags, enodes;
  double length = 0;
  std::size_t edges = 0;
  gmsh::vectorpair curves;
  gmsh::model::getEntities(curves, 1);
  for (const auto& [dim, tag] : curves) {
    gmsh::model::mesh::getElements(types, etags, enodes, dim, tag);
    for (const auto& e : etags)
      edges += e.size();
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
    length += std::hypot(x1 - x0, y1 - y0); // at most the curve's length
  }
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  double area = 0;
  for (const auto& [dim, tag] : surfaces) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
    area += (x1 - x0) * (y1 - y0); // at least the surface's area
  }
  if (edges == 0 || !(length > 0))
    return 0;
  const double h = length / double(edges); // at most the mean edge: an over-estimate follows
  return 0.5 * area / (std::sqrt(3.0) / 4 * h * h);
}

struct GmshSession {
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
};

/// Opens @p file with gmsh in a forked child first: gmsh trusts the file,
/// and a crash of its reader on what checkMshFile let through must cost an
/// Error, not the process. The child only opens the file and leaves with
/// _exit; when fork itself fails the in-process read goes on (checked).
void probeGmshInChild(const std::string& file) {
  const pid_t pid = ::fork();
  if (pid < 0)
    return;
  if (pid == 0) {
    int code = 0;
    try {
      gmsh::initialize(0, nullptr, false);
      gmsh::option::setNumber("General.Terminal", 0);
      gmsh::option::setNumber("General.Verbosity", 0);
      gmsh::open(file);
    } catch (...) {
      code = 1; // an exception is reported by the read in the parent
    }
    ::_exit(code);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      return;
  if (WIFSIGNALED(status))
    throw Error("gmsh's reader crashed on " + file + " (signal " +
                    std::to_string(WTERMSIG(status)) + ")",
                ErrorContext{file, 0, ""});
}
} // namespace

Mesh readGmsh(const std::filesystem::path& path, GmshProbe probe) {
  const std::string file = path.string();
  if (!std::filesystem::exists(path))
    throw Error("mesh file not found", ErrorContext{file, 0, ""});
  const std::string ext = path.extension().string();
  if (ext != ".msh" && ext != ".geo")
    throw Error("mesh file must be .msh or .geo, got '" + ext + "'", ErrorContext{file, 0, ""});
  core::checkRegularInput(path, "mesh file", core::kMaxMeshBytes); // gmsh would block on a FIFO

  std::lock_guard<std::mutex> lock(gmsh_mutex);
  if (ext == ".msh") {
    checkMshFile(path);
    if (probe == GmshProbe::kChild)
      probeGmshInChild(file);
  }
  GmshSession session;
  Mesh m;
  m.source = file;
  try {
    gmsh::open(file);
    if (ext == ".geo") {
      // Mesh the curves first and refuse before the surfaces when their edge
      // length asks for more than fits. A floor of 1e-6 of the model's size
      // keeps even this step short for a tiny lc; any mesh it changes is
      // refused (its estimate exceeds kMaxNodes), so a kept mesh is as asked.
      double x0, y0, z0, x1, y1, z1, floor_before = 0;
      gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
      gmsh::option::getNumber("Mesh.MeshSizeMin", floor_before);
      gmsh::option::setNumber("Mesh.MeshSizeMin",
                              std::max(floor_before, 1e-6 * std::hypot(x1 - x0, y1 - y0)));
      gmsh::model::mesh::generate(1);
      gmsh::option::setNumber("Mesh.MeshSizeMin", floor_before);
      requireRunMemory(estimateSurfaceNodes(), "the mesh of " + file, ErrorContext{file, 0, "lc"});
      gmsh::model::mesh::generate(2);
    }

    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, true, false);
    std::unordered_map<std::size_t, int> index;
    index.reserve(tags.size());
    for (std::size_t k = 0; k < tags.size(); ++k) {
      if (index.count(tags[k]))
        continue;
      index[tags[k]] = static_cast<int>(m.nodes.size());
      m.nodes.emplace_back(coord[3 * k], coord[3 * k + 1]);
      // z below round-off of the plan size counts as 0 (flat meshes stay flat).
      const double z = coord[3 * k + 2];
      m.z.push_back(std::abs(z) > 1e-12 * (1 + std::abs(coord[3 * k])) ? z : 0.0);
    }

    // Regions: physical surfaces; a surface entity without one falls in "all".
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    std::map<int, int> region_of_entity;
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, 2);
    for (const auto& [dim, tag] : groups) {
      std::string name;
      gmsh::model::getPhysicalName(dim, tag, name);
      if (name.empty())
        name = std::to_string(tag);
      std::vector<int> ents;
      gmsh::model::getEntitiesForPhysicalGroup(dim, tag, ents);
      const int r = static_cast<int>(m.regions.size());
      m.regions.push_back(name);
      for (int ent : ents)
        region_of_entity[ent] = r;
    }
    int all_region = -1;
    for (const auto& [dim, ent] : surfaces) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(types, etags, enodes, dim, ent);
      int region;
      auto it = region_of_entity.find(ent);
      if (it != region_of_entity.end()) {
        region = it->second;
      } else {
        if (!groups.empty())
          continue; // gmsh only saves physical elements; mirror that
        if (all_region < 0) {
          all_region = static_cast<int>(m.regions.size());
          m.regions.push_back("all");
        }
        region = all_region;
      }
      for (std::size_t t = 0; t < types.size(); ++t) {
        if (types[t] != 2)
          continue; // 3-node triangle
        for (std::size_t k = 0; k + 2 < enodes[t].size(); k += 3) {
          m.triangles.push_back(
              {index.at(enodes[t][k]), index.at(enodes[t][k + 1]), index.at(enodes[t][k + 2])});
          m.region_of.push_back(region);
        }
      }
    }

    // Node sets: physical curves and points.
    for (int dim : {0, 1}) {
      gmsh::vectorpair g;
      gmsh::model::getPhysicalGroups(g, dim);
      for (const auto& [d, tag] : g) {
        std::string name;
        gmsh::model::getPhysicalName(d, tag, name);
        if (name.empty())
          name = std::to_string(tag);
        std::vector<std::size_t> ntags;
        std::vector<double> c;
        gmsh::model::mesh::getNodesForPhysicalGroup(d, tag, ntags, c);
        auto& set = m.node_sets[name];
        for (auto nt : ntags)
          set.push_back(index.at(nt));
      }
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(std::string("cannot read mesh: ") + e.what(), ErrorContext{file, 0, ""});
  } catch (...) {
    throw Error("cannot read mesh (gmsh failed)", ErrorContext{file, 0, ""});
  }
  if (m.triangles.empty())
    throw Error("mesh has no 3-node triangles", ErrorContext{file, 0, ""});
  // Keep only nodes used by triangles (gmsh also returns e.g. circle centres).
  std::vector<int> renum(m.nodes.size(), -1);
  std::vector<Eigen::Vector2d> used;
  std::vector<double> used_z;
  for (auto& t : m.triangles)
    for (int& i : t) {
      if (renum[i] < 0) {
        renum[i] = static_cast<int>(used.size());
        used.push_back(m.nodes[i]);
        used_z.push_back(m.z[i]);
      }
      i = renum[i];
    }
  m.nodes = std::move(used);
  m.z = std::move(used_z);
  for (auto& [name, set] : m.node_sets) {
    std::vector<int> kept;
    for (int i : set)
      if (renum[i] >= 0)
        kept.push_back(renum[i]);
    set = std::move(kept);
  }
  finalizeMesh(m);
  return m;
}

} // namespace lamina::membrane
