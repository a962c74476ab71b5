#include "membrane/io/gmsh_reader.hpp"

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "membrane/io/msh_check.hpp"

#include <gmsh.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace lamina::membrane {

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

/// One use of gmsh's global state: initialize quietly, and on exit finalize
/// and give OpenMP back the thread count gmsh's start-up replaced with its own.
struct GmshSession {
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() {
    gmsh::finalize();
    omp_set_num_threads(threads_); // gmsh sets OpenMP's thread count to its own (1)
  }
  int threads_ = omp_get_max_threads(); ///< OpenMP's thread count before gmsh started
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

/// Refuses (lamina::Error naming @p path) a missing file, an extension
/// @p ext other than .msh and .geo, and anything but a regular file of at
/// most core::kMaxMeshBytes (gmsh would block on a FIFO).
void checkMeshPath(const std::filesystem::path& path, const std::string& ext) {
  const std::string file = path.string();
  if (!std::filesystem::exists(path))
    throw Error("mesh file not found", ErrorContext{file, 0, ""});
  if (ext != ".msh" && ext != ".geo")
    throw Error("mesh file must be .msh or .geo, got '" + ext + "'", ErrorContext{file, 0, ""});
  core::checkRegularInput(path, "mesh file", core::kMaxMeshBytes);
}

/// Meshes the open .geo model @p file in 2D. The curves are meshed first and
/// the surfaces refused when their edge length asks for more than fits
/// (requireRunMemory). A floor of 1e-6 of the model's size keeps even this
/// step short for a tiny lc; any mesh it changes is refused (its estimate
/// exceeds kMaxNodes), so a kept mesh is as asked.
void meshGeo(const std::string& file) {
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

/// gmsh's node tag -> index in Mesh::nodes.
using NodeIndex = std::unordered_map<std::size_t, int>;

/// Appends every node of the open gmsh model to @p m (the first of a
/// repeated tag); z below round-off of the plan size counts as 0, so flat
/// meshes stay flat. @return the tag -> index map
NodeIndex readNodes(Mesh& m) {
  std::vector<std::size_t> tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, true, false);
  NodeIndex index;
  index.reserve(tags.size());
  for (std::size_t k = 0; k < tags.size(); ++k) {
    if (index.count(tags[k]))
      continue;
    index[tags[k]] = static_cast<int>(m.nodes.size());
    m.node_id.push_back(tags[k]);
    m.nodes.emplace_back(coord[3 * k], coord[3 * k + 1]);
    const double z = coord[3 * k + 2];
    m.z.push_back(std::abs(z) > 1e-12 * (1 + std::abs(coord[3 * k])) ? z : 0.0);
  }
  return index;
}

/// @return the name of physical group (@p dim, @p tag): its own, else its tag
std::string physicalName(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? std::to_string(tag) : name;
}

/// Adds the physical surfaces of the open gmsh model to @p m's regions.
/// @return surface entity -> region index
std::map<int, int> readRegions(Mesh& m) {
  std::map<int, int> region_of_entity;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  for (const auto& [dim, tag] : groups) {
    std::vector<int> ents;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, ents);
    const int r = static_cast<int>(m.regions.size());
    m.regions.push_back(physicalName(dim, tag));
    for (int ent : ents)
      region_of_entity[ent] = r;
  }
  return region_of_entity;
}

/// Adds the 3-node triangles of the open gmsh model's surfaces to @p m, with
/// their regions: physical surfaces; a surface entity without one falls in
/// "all" when the model has no physical surface, else is skipped (gmsh only
/// saves physical elements; mirror that).
void readTriangles(const NodeIndex& index, Mesh& m) {
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  const std::map<int, int> region_of_entity = readRegions(m);
  const bool any_physical = !m.regions.empty();
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
      if (any_physical)
        continue;
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
        m.element_id.push_back(etags[t][k / 3]);
        m.region_of.push_back(region);
      }
    }
  }
}

/// Adds the physical curves and points of the open gmsh model to @p m's node sets.
void readNodeSets(const NodeIndex& index, Mesh& m) {
  for (int dim : {0, 1}) {
    gmsh::vectorpair g;
    gmsh::model::getPhysicalGroups(g, dim);
    for (const auto& [d, tag] : g) {
      std::vector<std::size_t> ntags;
      std::vector<double> c;
      gmsh::model::mesh::getNodesForPhysicalGroup(d, tag, ntags, c);
      auto& set = m.node_sets[physicalName(d, tag)];
      for (auto nt : ntags)
        set.push_back(index.at(nt));
    }
  }
}

/// Keeps only the nodes of @p m used by triangles (gmsh also returns e.g.
/// circle centres), numbered in order of first use; node sets and node tags follow.
void keepUsedNodes(Mesh& m) {
  std::vector<int> renum(m.nodes.size(), -1);
  int used = 0;
  for (const auto& t : m.triangles)
    for (int i : t)
      if (renum[i] < 0)
        renum[i] = used++;
  renumberNodes(m, renum);
}
} // namespace

Mesh readGmsh(const std::filesystem::path& path, GmshProbe probe) {
  const std::string file = path.string();
  const std::string ext = path.extension().string();
  checkMeshPath(path, ext);
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
    if (ext == ".geo")
      meshGeo(file);
    const NodeIndex index = readNodes(m);
    readTriangles(index, m);
    readNodeSets(index, m);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(std::string("cannot read mesh: ") + e.what(), ErrorContext{file, 0, ""});
  } catch (...) {
    throw Error("cannot read mesh (gmsh failed)", ErrorContext{file, 0, ""});
  }
  if (m.triangles.empty())
    throw Error("mesh has no 3-node triangles", ErrorContext{file, 0, ""});
  keepUsedNodes(m);
  finalizeMesh(m);
  return m;
}

} // namespace lamina::membrane
