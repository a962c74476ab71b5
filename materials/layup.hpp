#pragma once
/// @file layup.hpp
/// @brief Layered membranes: the exact thickness average of ply stiffnesses.
///
/// The membrane kinematics put the same strain through the thickness, so a
/// stack of plies (h_k, D_k rotated by theta_k about z) acts exactly as
/// D = sum h_k R(theta_k) D_k R(theta_k)^T / h and rho = sum h_k rho_k / h,
/// h = sum h_k (DESIGN.md, "Layered membranes").

#include "materials/material.hpp"

#include <functional>
#include <string>
#include <vector>

namespace lamina::materials {

/// Looks a ply material up by name (library first, then catalog, for instance).
using MaterialLookup = std::function<Material(const std::string&)>;

/// Largest ply angle accepted, in degrees either way (one full turn: -45
/// and 315 name the same ply; beyond a turn an angle is a typing error).
inline constexpr double kMaxPlyAngleDeg = 360.0;

/// Parses "MATERIAL:ANGLE_DEG:THICKNESS_M"; throws lamina::Error on bad text.
Ply parsePly(const std::string& text);

/// Builds the layup entry @p name (kind "layup") from @p plies. Throws
/// lamina::Error for an empty stack, a non-positive thickness, an angle
/// beyond kMaxPlyAngleDeg or an unknown ply material.
Material makeLayup(const std::string& name, const std::vector<Ply>& plies,
                   const MaterialLookup& lookup);

} // namespace lamina::materials
