#pragma once
/// @file cell.hpp
/// @brief The description of a unit cell as read from a cell file
/// (cases/cells/*.toml): resolution, size, phases, inclusion groups.
///
/// Format (full reference in docs/homogenize.md):
/// ```toml
/// [cell]
/// resolution = 32            # N or [N1, N2, N3] voxels
/// size = [20e-6, 20e-6, 20e-6]  # optional, cell edge lengths in metres
///                            # (absent: scale-free cell of edge 1, no micro-inertia)
/// composite_voxels = true    # default: cut voxels get a laminate stiffness
/// [[phases]]                 # the first phase is the matrix
/// name = "soft"
/// catalog = "polyurea-soft"  # or law = "isotropic" / "anisotropic" / "gvbo" ...
/// J = [1.0, 0.95]            # gvbo only: states to homogenize at
/// [[inclusions]]
/// phase = "hard"
/// shape = "ellipsoid"        # sphere, ellipsoid, fiber, layer
/// semi_axes = [1, 1, 2]
/// orientation = { axis = [0, 1, 0], angle = 45 }   # degrees
/// placement = "random"       # single, lattice, random
/// volume_fraction = 0.19
/// count = 8
/// seed = 1
/// min_gap = 0.02
/// ```

#include "core/enum_names.hpp"
#include "micro/inclusion.hpp"
#include "micro/phase.hpp"
#include "micro/voxel_image.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lamina::micro {

/// Most voxels along one direction (4096^3 voxels already need ~1 TB).
inline constexpr int kMaxResolution = 4096;
/// Most inclusions in one cell: placement tests every pair for overlap, so
/// the work grows with the square of the count.
inline constexpr std::int64_t kMaxInclusions = 10000;
/// Most random placement attempts per inclusion.
inline constexpr std::int64_t kMaxAttempts = 1000000;
/// Most overlap tests of one cell's random placement, all groups together
/// (each attempt tests its candidate against every inclusion placed so
/// far): bounds the worst case of the limits above (10,000 inclusions x
/// 1,000,000 attempts, hours) while 10,000 spheres placed at a few attempts
/// each (about 5e7 tests per attempt) still fit. docs/reliability.md has
/// the times.
inline constexpr std::int64_t kMaxOverlapTests = 400000000;

/// How the inclusions of a group are placed.
enum class Placement { Single, Lattice, Random };
/// The cell-file names of Placement (`placement` of an [[inclusions]] table).
inline constexpr auto kPlacementNames = core::enumNames<Placement>({{"single", Placement::Single},
                                                                    {"lattice", Placement::Lattice},
                                                                    {"random", Placement::Random}});

/// One `[[inclusions]]` table: a prototype inclusion and how to place copies.
struct InclusionGroup {
  Inclusion prototype; ///< shape, phase, semi-axes/radius/thickness, orientation
  Placement placement = Placement::Single;
  std::optional<double> volume_fraction; ///< target analytic fraction of the group
  std::array<int, 3> lattice{1, 1, 1};   ///< copies along x, y, z (lattice)
  int count = 0;                         ///< random: number of copies (0: from the fraction)
  std::uint64_t seed = 1;                ///< random: seed of the generator
  double min_gap = 0;                    ///< minimum distance between inclusions
  int max_attempts = 200000;             ///< random: attempts per inclusion before giving up
  std::string key;                       ///< "inclusions[i]" for messages
};

/// Largest cell edge accepted as metres (m): above it `size` cannot be a
/// unit cell of a membrane material (and is most likely a unit-less size
/// written before sizes were metres).
inline constexpr double kMaxCellEdge = 0.1;

/// A cell file, parsed and validated (nothing placed yet).
struct CellSpec {
  std::string file;                               ///< path it was read from
  std::string text;                               ///< the full file text (provenance)
  std::vector<std::string> overrides; ///< the --set KEY=VALUE applied over text (provenance)
  std::string description;                        ///< optional one-line description
  std::array<int, 3> resolution{32, 32, 32};      ///< voxels along x, y, z
  Eigen::Vector3d size = Eigen::Vector3d::Ones(); ///< edge lengths (m; 1 if not given)
  bool physical_size = false; ///< `size` was given (metres): the cell has a scale (micro-inertia)
  std::optional<ImageSource> image;          ///< set for an image cell (`image = "PATH"`)
  std::optional<Eigen::Vector3d> voxel_size; ///< image cells: `voxel_size` (m; overrides the file)
  std::optional<bool> composite_voxels;      ///< generated cells: `composite_voxels`
  std::vector<Phase> phases;                 ///< phases[0] is the matrix
  std::vector<InclusionGroup> groups;        ///< inclusion groups, placed in order
  /// random placement's work bound (overlap tests); only code lowers it
  /// (tests, fuzzers), no key sets it
  std::int64_t max_overlap_tests = kMaxOverlapTests;

  /// @return the index of the phase named @p name, -1 if none
  int phaseIndex(const std::string& name) const;
  /// @return the J states of the swept gvbo phase ({1.0} if none has a list)
  std::vector<double> sweepStates() const;
  /// @return the stiffness of every phase at matrix state @p J
  std::vector<materials::Stiffness> stiffnessesAt(double J) const;
  /// @return the density of every phase
  std::vector<double> densities() const;
};

/// Reads and validates a cell file. @p catalog is consulted only for phases
/// with `catalog = "NAME"`. Throws lamina::Error naming the file, line and key
/// for a malformed file (unknown key, negative radius, unknown phase...).
/// The `--set KEY=VALUE` @p overrides are applied to the file's keys first
/// (core::applyOverride); an error about an overridden value names the --set.
CellSpec readCell(const std::filesystem::path& path, const CatalogProvider& catalog,
                  const std::vector<std::string>& overrides = {});

/// As readCell, from text; @p source names it in messages.
CellSpec readCellString(const std::string& text, const std::string& source,
                        const CatalogProvider& catalog,
                        const std::vector<std::string>& overrides = {});

/// A provider that loads materials::Catalog(materials::Catalog::defaultPath())
/// (or @p path if non-empty) once, on first use.
CatalogProvider lazyCatalog(const std::filesystem::path& path = {});

} // namespace lamina::micro
