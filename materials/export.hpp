#pragma once
/// @file export.hpp
/// @brief Material cards for other codes and the JSON view of an entry.
///
/// - abaqus:   *MATERIAL, *ELASTIC, TYPE=ANISOTROPIC (21 values D1111 D1122
///             D2222 D1133 D2233 D3333 D1112 D2212 D3312 D1212 D1113 D2213
///             D3313 D1213 D1313 D1123 D2223 D3323 D1223 D1323 D2323, 8 per
///             line), *DENSITY.
/// - calculix: the same card with *ELASTIC, TYPE=ANISO, 9 significant digits
///             so that a data line stays within CalculiX's 132 columns.
/// - lsdyna:   *MAT_ANISOTROPIC_ELASTIC_TITLE+ (MAT_002, large format: the "+"
///             suffix of LS-DYNA R7.1+, 20-column fields, 13 significant
///             digits): MID RO C11 C12 C22 C13 C23 C33 / C14 C24 C34 C44 C15
///             C25 C35 C45 / C55 C16 C26 C36 C46 C56 C66 AOPT / XP YP ZP A1 A2
///             A3 MACF / V1 V2 V3 D1 D2 D3 BETA REF, with AOPT = 2, A = x,
///             D = y (material axes = global axes). Order xx yy zz xy yz zx.
/// - lsdyna-small: the same card in standard format (10-column fields, 80
///             columns per card, 3-4 significant digits) for older readers.
/// - json:     the object of materialToJson().

#include "core/enum_names.hpp"
#include "materials/material.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <utility>

namespace lamina::materials {

/// The card formats of exportCard().
enum class ExportFormat { Abaqus, Calculix, Lsdyna, LsdynaSmall, Json };

/// The --format names of every format: the one table of them.
inline constexpr auto kExportFormatNames =
    core::enumNames<ExportFormat>({{"abaqus", ExportFormat::Abaqus},
                                   {"calculix", ExportFormat::Calculix},
                                   {"lsdyna", ExportFormat::Lsdyna},
                                   {"lsdyna-small", ExportFormat::LsdynaSmall},
                                   {"json", ExportFormat::Json}});

/// @return the format named @p name; throws lamina::Error (naming --format) otherwise
ExportFormat parseExportFormat(const std::string& name);

/// @return the card text of @p m in @p format. A reduced-order entry (a
/// nonlinear law) exports as json only; a card format is an error naming
/// --format.
std::string exportCard(const Material& m, ExportFormat format);

/// @return a 6x6 matrix as 6 JSON rows of 6 numbers (the "C" of every JSON
/// output: Pa, lamina order)
nlohmann::json matrixToJson(const Matrix6& c);

/// @return {"name", "C", "density", "kind", "symmetry", "symmetry_axis",
/// "anisotropy_index", "engineering": {...}, "thickness", "plies",
/// "provenance", "side_file", "side_checksum", "phases": [{"name",
/// "density", "law", "C", "gvbo": {E0, nu0, Et, ...}}]} (optional members
/// only when present).
nlohmann::json materialToJson(const Material& m);

} // namespace lamina::materials
