#pragma once
/// @file reduced_order_run.hpp
/// @brief The reduced-order mode of the `homogenize` program: a cell file's
/// reduced-order model (reduced_order_builder.hpp) written as one library
/// entry of kind "reduced-order" with its arrays in an HDF5 side file
/// (materials/reduced_order.hpp), in one transaction.

#include "homogenize/reduced_order_builder.hpp"
#include "materials/library.hpp"
#include "materials/material.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace lamina::homogenize {

/// @return the phases of @p spec as a reduced-order model keeps them:
/// name, law spec (micro::Phase::lawSpec) and density
std::vector<materials::ReducedOrderPhase> reducedOrderPhases(const micro::CellSpec& spec);

/// Throws lamina::Error naming the cell file unless every voxel of @p cell
/// has its phase's single stiffness: a yarn following its path rotates its
/// phase voxel by voxel (UnitCell::oriented), so its phase has no one L0.
/// Composite voxels are fine: the plain map (the voxel centre's phase) is
/// what the reduced-order build uses. A void phase (a pore) is refused.
void checkReducible(const micro::CellSpec& spec, const micro::UnitCell& cell);

/// checkReducible, then the build of @p cell's plain phase map, with
/// micro-inertia when the cell has a size in metres (spec.physical_size).
ReducedOrderResult buildReducedOrder(const micro::CellSpec& spec, const micro::UnitCell& cell,
                                     const ReducedOrderOptions& options);

/// @return the doubles of state per material point of the reduced-order
/// law of @p m: for every partition its strain (6) and its phase law's
/// stateSize()
int stateDoublesPerPoint(const materials::ReducedOrderModel& m);

/// The library entry of a build: kind "reduced-order", C, density, phases,
/// with micro-inertia `dispersion` (D_lin, kg/m) and `cell_size` (m), and
/// the provenance of every homogenized entry (cellProvenance) plus the
/// partitions, the solver, its tolerance and the build's cost.
materials::Material makeReducedOrderEntry(const std::string& name, const micro::CellSpec& spec,
                                          const micro::UnitCell& cell,
                                          const ReducedOrderResult& result,
                                          const ReducedOrderOptions& options);

/// Checks @p name against @p library (before anything is computed), builds
/// the model and adds the entry with its side file
/// (materials::writeReducedOrderArrays) in one transaction: all or nothing.
ReducedOrderResult addReducedOrderEntry(const micro::CellSpec& spec, const micro::UnitCell& cell,
                                        const std::string& name,
                                        const ReducedOrderOptions& options,
                                        materials::Library& library, bool overwrite);

/// The `--json` summary: name, library (libraryJsonPath of @p library, the
/// file that received the entry), partitions, partition_phase, fractions,
/// partitions_per_phase, C (Pa), density, dispersion (with a size), solves,
/// iterations, residual, wall_s, peak_memory_bytes, influence_doubles,
/// state_doubles_per_point.
nlohmann::json reducedOrderJson(const std::string& name, const ReducedOrderResult& result,
                                const std::filesystem::path& library);

/// The human summary (several lines): partitions per phase, solves,
/// iterations, seconds, memory, state doubles per point.
std::string reducedOrderSummary(const std::string& name, const ReducedOrderResult& result);

} // namespace lamina::homogenize
