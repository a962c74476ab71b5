#pragma once
/// @file gmsh_reader.hpp
/// @brief Triangle meshes (model/mesh.hpp) from gmsh files: a .msh file read,
/// or a .geo file meshed, through the gmsh C++ API. A .msh file passes our
/// own structural check (msh_check.hpp) before gmsh sees it.

#include "membrane/model/mesh.hpp"

#include <filesystem>

namespace lamina::membrane {

/// Where gmsh's own reader first opens a .msh file that checkMshFile
/// (membrane/io/msh_check.hpp) accepted.
enum class GmshProbe {
  kChild,    ///< first in a forked child: a crash there is a clean lamina::Error
  kInProcess ///< only in this process (msh_fuzzer: a gap in the check is a finding)
};

/// Reads a 2D triangle mesh from a gmsh .msh file, or meshes a .geo file
/// (2D), through the gmsh C++ API. Physical surfaces become regions (a mesh
/// without physical surfaces has one region "all"); physical curves and
/// points become node sets. A .msh file passes checkMshFile first and, with
/// @p probe kChild, is read once by gmsh in a forked child: a signal there
/// ("gmsh's reader crashed on FILE (signal 11)") is an Error, not a crash.
/// Throws lamina::Error naming the file when it is missing, unreadable,
/// malformed, or has no triangles.
Mesh readGmsh(const std::filesystem::path& path, GmshProbe probe = GmshProbe::kChild);

} // namespace lamina::membrane
