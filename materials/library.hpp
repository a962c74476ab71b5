#pragma once
/// @file library.hpp
/// @brief The materials library: one TOML text file of Material entries.
///
/// Format (see docs/materials.md, "The library file"): a `[lamina]` header table with
/// `format = "lamina-materials-library"` and `version = 1`, then one table
/// `[materials."NAME"]` per entry with `kind`, `density`, `C` (6 rows of 6,
/// Pa, lamina order, 17 significant digits), optional `thickness`, `plies`,
/// `side_file`, `side_checksum` (fileChecksum of the side file) and a
/// `provenance` sub-table. A `reduced-order` entry (a reduced-order cell,
/// reduced_order_law.hpp) also has `[[materials."NAME".phases]]` tables
/// (name, density and the law as writeLawSpec writes it) and requires its
/// side file (the arrays of writeReducedOrderArrays) and its checksum.
///
/// Contract: add() and remove() take an exclusive lock on "<file>.lock",
/// re-read the file, apply the change and replace the file atomically (write
/// aside, fsync, rename). A failed or interrupted write leaves the previous
/// file intact; concurrent writers serialize and all their entries land.
/// Side files are part of the same transaction (add with a SideFileWriter),
/// and each write, under the lock, removes what interrupted writers left
/// (temporaries, side files no entry names). A library that is a symlink
/// stays one (the file it points to is written) and keeps its permissions;
/// side files take the library's permission bits, and the side folder is
/// never more permissive than the library (x added where r is set). A
/// command adding several entries adds them in one transaction: all or none.
/// Reading validates strictly: a file that is not a lamina library, an
/// unknown key, a malformed or non-positive-definite entry is an error naming
/// the file, the line and the key.

#include "materials/material.hpp"

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace lamina::materials {

/// The library file and its entries (a snapshot taken at load time).
class Library {
public:
  /// Environment variable naming the library file when --library is not given.
  static constexpr const char* kEnvVar = "LAMINA_LIBRARY";

  /// Resolves the library path: @p cli_path if non-empty, else $LAMINA_LIBRARY,
  /// else $XDG_DATA_HOME/lamina/library.toml, else ~/.local/share/lamina/library.toml.
  static std::filesystem::path resolvePath(const std::string& cli_path);

  /// Loads @p path; a missing file is an empty library (created on first add).
  explicit Library(std::filesystem::path path);

  /// @return the file path
  const std::filesystem::path& path() const { return path_; }
  /// @return the folder side-file paths are relative to: that of the library
  /// file once symlinks are resolved
  std::filesystem::path folder() const;
  /// @return the entry names in sorted order
  std::vector<std::string> names() const;
  /// @return whether @p name is present
  bool contains(const std::string& name) const { return entries_.count(name) > 0; }
  /// @return the entry @p name; throws lamina::Error naming the library path
  /// and listing what it holds when absent
  const Material& get(const std::string& name) const;

  /// Writes the side file of an entry to the path it is given (and, if it
  /// wants, companion files of the same stem beside it, e.g. an .xdmf that
  /// names the .h5 by its file name).
  using SideFileWriter = std::function<void(const std::filesystem::path& h5)>;

  /// Adds @p m (validated first) and writes the file. With @p overwrite false an
  /// existing entry of the same name is an error and nothing is written.
  void add(const Material& m, bool overwrite = false);

  /// Adds @p m with a side file, in one transaction under the library's lock:
  /// @p write_side writes into a fresh temporary folder inside the side
  /// folder "<stem>.side/" (beside the library file, symlinks resolved)
  /// under a name unique to this transaction, "<name>.XXXXXX.h5"; its files
  /// are renamed into the side folder, m.side_file is set to that path
  /// (relative to folder()), m.side_checksum to the fileChecksum of the .h5
  /// written, and the library is written: the commit point.
  /// On any failure the new files are removed and the library is unchanged;
  /// after the commit the files of a replaced entry are removed.
  void add(Material m, bool overwrite, const SideFileWriter& write_side);

  /// One entry of a transaction: the material and, if it has one, the
  /// writer of its side file.
  struct Addition {
    Material material;         ///< the entry (validated by add)
    SideFileWriter write_side; ///< its side file, or empty for none
  };

  /// Adds every entry of @p additions in one transaction under the lock
  /// (as the single add above): all entries land or none does. Names that
  /// repeat within @p additions are an error, and so is a name already in
  /// the library unless @p overwrite, before anything is written.
  void add(std::vector<Addition> additions, bool overwrite);

  /// Throws lamina::Error when two of @p names are equal or (unless
  /// @p overwrite) one is already in the library (as loaded; add() checks
  /// again under the lock). @p option names the argument in the message
  /// (e.g. "--name").
  void checkNewNames(const std::vector<std::string>& names, bool overwrite,
                     const std::string& option) const;
  /// Removes entry @p name and writes the file; error if absent.
  void remove(const std::string& name);

  /// Serializes entries to the library's TOML text.
  static std::string serialize(const std::map<std::string, Material>& entries);
  /// Parses library text; @p source names it in errors.
  static std::map<std::string, Material> parse(const std::string& text, const std::string& source);

private:
  void reload();
  /// Under the lock: removes debris of interrupted writes (the library's
  /// temporaries, temporary side folders) and side files no entry names.
  void sweep() const;
  /// @return "<stem>.side", the side folder relative to folder()
  std::filesystem::path sideFolder() const;
  std::filesystem::path path_;
  std::map<std::string, Material> entries_;
};

} // namespace lamina::materials
