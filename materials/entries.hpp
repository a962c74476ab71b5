#pragma once
/// @file entries.hpp
/// @brief What the `materials` commands make and show, as functions that the
/// program (cli.cpp) and the Python module (lamina.Library) share, so that
/// an entry added from either has the same fields, checks and messages, and
/// `show --json` and `lib[name]` the same content.

#include "materials/catalog.hpp"
#include "materials/library.hpp"
#include "materials/material.hpp"
#include "materials/material_source.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace lamina::materials {

/// Records in the provenance of @p m who made it: `program` = @p program
/// (e.g. "materials add"), `version` (lamina's) and `time` (UTC, ISO 8601).
void stampProvenance(Material& m, const std::string& program);

/// @return the entry @p name of the catalog material @p key (kind
/// "catalog", provenance `catalog_key` and stampProvenance(@p program)):
/// what `materials add NAME --from-catalog KEY` adds. Throws lamina::Error
/// naming the catalog and its entries when @p key is not in @p catalog.
Material catalogEntry(const Catalog& catalog, const std::string& key, const std::string& name,
                      const std::string& program);

/// @return the layup entry @p name of @p plies (makeLayup, each ply's
/// material looked up in @p source: library first, then catalog), with
/// stampProvenance(@p program): what `materials layup` adds
Material layupEntry(const std::string& name, const std::vector<Ply>& plies, MaterialSource& source,
                    const std::string& program);

/// @return what `materials show NAME --json` prints for the entry @p m of
/// @p library: materialToJson(m) and, for a reduced-order entry, each
/// phase's `partitions`, `state_doubles` and `nonlinear_partitions` (its
/// side file read and checked, readReducedOrderEntry)
nlohmann::json showJson(const Library& library, const Material& m);

} // namespace lamina::materials
