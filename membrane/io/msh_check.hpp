#pragma once
/// @file msh_check.hpp
/// @brief Our own structural check of a gmsh .msh file, run before gmsh's
/// reader sees it.
///
/// Debian's gmsh 4.8 trusts the file: an element naming a node tag that
/// does not fit an int (e.g. a mutated byte in `$Elements`) makes
/// `GModel::_readMSH4` index its node cache out of bounds and die with
/// SIGSEGV (found by fuzz/msh_fuzzer.cpp). This check reads the
/// whole file as the MSH format defines it (gmsh reference manual, "MSH file
/// format", versions 2.2 and 4.1, ASCII and binary) and refuses, before gmsh
/// opens it, anything gmsh would trust: a version other than 2.2 or 4.1, a
/// section other than `$MeshFormat`, `$PhysicalNames`, `$Entities`,
/// `$Nodes`, `$Elements` and `$Comments`, a count larger than the rest of
/// the file can hold or different from what follows, a tag outside 1 to
/// 2^31 - 1 or outside the range its header declares, a repeated node or
/// element tag, a non-finite coordinate, an unknown element type, an
/// element whose node does not exist, a block naming a missing entity.

#include <filesystem>
#include <string>

namespace lamina::membrane {

/// Checks the .msh file at @p path (see the file comment). Throws
/// lamina::Error naming the file, the section and the line (ASCII) or byte
/// offset (binary) and the node or element at fault; returns when gmsh may
/// read the file.
void checkMshFile(const std::filesystem::path& path);

/// Checks the .msh content @p text as checkMshFile does; @p file names it
/// in the errors.
void checkMshText(const std::string& text, const std::string& file);

} // namespace lamina::membrane
