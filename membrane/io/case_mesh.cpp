/// @file case_mesh.cpp
/// @brief [mesh] of a case: structured rectangle or gmsh file.

#include "membrane/io/case_builders.hpp"
#include "membrane/io/gmsh_reader.hpp"
#include "membrane/model/mesh_ordering.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/resources.hpp"
#include "core/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

namespace lamina::membrane::case_io {

namespace {
/// What a [mesh] is (its `type`).
enum class MeshType { Rectangle, Gmsh };
constexpr auto kMeshTypes =
    core::enumNames<MeshType>({{"rectangle", MeshType::Rectangle}, {"gmsh", MeshType::Gmsh}});
/// How the nodes of a gmsh mesh are numbered for the run (`renumber`).
enum class Renumber { Rcm, None };
constexpr auto kRenumbers =
    core::enumNames<Renumber>({{"rcm", Renumber::Rcm}, {"none", Renumber::None}});
} // namespace

Mesh readMesh(const core::TableReader& r, const std::filesystem::path& case_path) {
  const MeshType type = r.getChoice("type", kMeshTypes, MeshType::Rectangle);
  if (type == MeshType::Rectangle) {
    const double Lx = r.getDouble("Lx");
    const double Ly = r.getDouble("Ly", Lx);
    const auto nx = r.getIntIn("nx", 1, 100000);
    const auto ny = r.getIntIn("ny", 1, 100000, nx);
    if (!(Lx > 0))
      r.fail("Lx", "must be > 0");
    if (!(Ly > 0))
      r.fail("Ly", "must be > 0");
    requireRunMemory(double(nx + 1) * double(ny + 1),
                     "a " + std::to_string(nx) + " x " + std::to_string(ny) + " rectangle",
                     {r.file(), 0, r.path("nx")});
    return structuredRectangle(Lx, Ly, static_cast<int>(nx), static_cast<int>(ny));
  }
  std::filesystem::path file = r.getString("file"); // MeshType::Gmsh
  const Renumber renumber = r.getChoice("renumber", kRenumbers, Renumber::Rcm);
  if (file.is_relative())
    file = case_path.parent_path() / file;
  if (!std::filesystem::exists(file))
    r.fail("file", "mesh file not found: " + file.string());
  Mesh mesh = readGmsh(file);
  if (renumber == Renumber::Rcm)
    orderForLocality(mesh);
  return mesh;
}

} // namespace lamina::membrane::case_io
