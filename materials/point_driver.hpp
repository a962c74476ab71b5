#pragma once
/// @file point_driver.hpp
/// @brief `materials drive`: one material point driven along a strain path
/// at a constant rate, the stress-strain history as CSV.
///
/// Paths (the driven strain e(t) = rate * t up to `to`, then back to zero
/// with `unload`; engineering strains of the deformation gradient F):
/// - uniaxial-strain: F = diag(1 + e, 1, 1) (eps_xx driven, others zero);
/// - confined: confined compression, F = diag(1 - e, 1, 1);
/// - shear: simple shear F = I + e e_x (x) e_y (eps_xy = e driven);
/// - uniaxial-stress: F = diag(1 + e, 1 + l_y, 1 + l_z) with l_y, l_z such
///   that sigma_yy = sigma_zz = 0 (Newton with the consistent tangent);
/// - biaxial-stress: equibiaxial plane stress, F = diag(1 + e, 1 + e, 1 +
///   l_z) with l_z such that sigma_zz = 0 (the same Newton on l_z alone): a
///   membrane under equibiaxial stretch, computed through F and
///   finiteIncrement(), independently of planeStressUpdate (plane_stress.hpp).
/// The lateral Newton stops when the free stresses are below 1e-10 of the
/// driven stress (at least 1 Pa) plus 1e-6 Pa.
/// Finite kinematics (default): each step F_n -> F goes through
/// finiteIncrement() (rotation-free frame of eq. 5, J = det F) and the
/// Cauchy stress is R sigma_hat R^T. Small kinematics: eps = sym(F - I),
/// J = 1 + tr eps, no rotation (what the FFT cell solver uses).
/// Output columns: t, eps = sym(F - I) (lamina order, engineering shear),
/// Cauchy sigma (Pa).

#include "core/enum_names.hpp"
#include "materials/law.hpp"
#include "materials/reduced_order_law.hpp"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lamina::materials {

/// The strain paths of `materials drive`.
enum class DrivePath { UniaxialStress, BiaxialStress, UniaxialStrain, Shear, Confined };
/// The command-line spellings of DrivePath (`--path` of materials drive and homogenize).
inline constexpr auto kDrivePathNames =
    core::enumNames<DrivePath>({{"uniaxial-stress", DrivePath::UniaxialStress},
                                {"biaxial-stress", DrivePath::BiaxialStress},
                                {"uniaxial-strain", DrivePath::UniaxialStrain},
                                {"shear", DrivePath::Shear},
                                {"confined", DrivePath::Confined}});
/// @return the command-line spelling ("uniaxial-stress", ...)
const char* toString(DrivePath p);

/// Small strain (sym(F - I), J = 1 + tr eps, no rotation) or finite deformation.
enum class Kinematics { Small, Finite };
/// The spellings of Kinematics (`--kinematics` of materials drive).
inline constexpr auto kKinematicsNames =
    core::enumNames<Kinematics>({{"finite", Kinematics::Finite}, {"small", Kinematics::Small}});

/// What to drive.
struct DriveOptions {
  DrivePath path = DrivePath::UniaxialStrain; ///< strain path
  double rate = 1.0;                          ///< driven strain rate (1/s), > 0
  double to = 0.1;                            ///< final driven strain (> 0; confined: compression)
  bool unload = false;                        ///< drive back to zero at the same rate
  int steps = 200;                            ///< steps per leg
  Kinematics kinematics = Kinematics::Finite; ///< finite (default) or small
};

/// Slowest driven strain rate accepted (1/s): at 1e-12 /s a strain of 1e-3
/// takes 30 years; below it a rate is a typo or an underflow (a denormal
/// rate makes dt = strain / rate overflow to infinity).
inline constexpr double kMinRate = 1e-12;
/// Fastest driven strain rate accepted (1/s): at 1e12 /s a strain of 1e-3
/// takes a femtosecond, far below the atomic vibration periods any continuum
/// law describes.
inline constexpr double kMaxRate = 1e12;

/// Throws lamina::Error naming @p option (e.g. "--rate") unless @p rate is
/// in [kMinRate, kMaxRate] (with @p allow_infinite, +inf too: an
/// instantaneous tangent).
void checkRate(double rate, const std::string& option, bool allow_infinite = false);

/// Throws lamina::Error naming @p option (e.g. "--to") unless @p to is a
/// positive finite strain, below 1 on the confined path (a compression of 1
/// crushes the point to zero volume).
void checkFinalStrain(DrivePath path, double to, const std::string& option);

/// One output row.
struct DriveRow {
  double t = 0;                    ///< s
  Vector6 eps = Vector6::Zero();   ///< sym(F - I), lamina order, engineering shear
  Vector6 sigma = Vector6::Zero(); ///< Cauchy stress, lamina order (Pa)
};

/// One accepted step, as drive() reports it to an observer (for outputs
/// beyond the stress, e.g. a reduced-order law's nonlinear dispersion).
struct DriveStep {
  int n = 0;                       ///< step number (1-based)
  double t = 0;                    ///< time at the end of the step (s)
  PointStep step;                  ///< the step in the law's rotation-free frame
  const double* state_n = nullptr; ///< the law's state at t_n (stateSize() doubles)
  /// rotation from the rotation-free frame to the global one (identity for
  /// small kinematics): a tensor X of the law's frame is R X R^T globally
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

/// Drives @p law; first row t = 0. @p observer (if set) sees every accepted
/// step before its state is committed. Throws lamina::Error on bad options
/// or when the lateral iteration of a stress path does not converge; an error of the
/// law (or of the observer) is rethrown with the step number and t in front
/// of its message, its context kept.
std::vector<DriveRow> drive(const ConstitutiveLaw& law, const DriveOptions& options,
                            const std::function<void(const DriveStep&)>& observer = {});

/// One row of `materials drive --nonlinear-dispersion`.
struct DispersionRow {
  double t = 0;                ///< s
  Matrix6 D = Matrix6::Zero(); ///< D_nonlin of eq. 40, global frame (kg/m, lamina order)
  double ratio = 0;            ///< max |D_nonlin| / max |D_lin| (law's frame)
};

/// @return an observer for drive() that appends, at every accepted step,
/// D_nonlin of @p law (ReducedOrderLaw::nonlinearDispersion of the step,
/// evaluated again with updateWithInfo from the same inputs, so of the same
/// converged strains) to @p rows: rotated to the global frame with the
/// step's R (a fourth-order tensor, as Stiffness::rotated), and its ratio
/// max |D_nonlin| / max |D_lin| taken in the law's frame (D_lin: the cell's
/// linear dispersion; inf when D_lin is zero and D_nonlin is not).
std::function<void(const DriveStep&)> recordNonlinearDispersion(const ReducedOrderLaw& law,
                                                                std::vector<DispersionRow>& rows);

/// Writes @p rows to @p path (17 significant digits) under the header
/// "t,D11,D12,...,D16,D22,...,D66,max_ratio": the 21 components of the upper
/// triangle row by row (lamina order xx yy zz xy yz xz, 1-based), kg/m.
void writeDispersionCsv(const std::filesystem::path& path, const std::vector<DispersionRow>& rows);

/// The CSV header of `materials drive`.
inline constexpr const char* kDriveHeader =
    "t,eps_xx,eps_yy,eps_zz,eps_xy,eps_yz,eps_xz,sig_xx,sig_yy,sig_zz,sig_xy,sig_yz,sig_xz";

/// Writes @p rows with kDriveHeader to @p path (17 significant digits).
void writeDriveCsv(const std::filesystem::path& path, const std::vector<DriveRow>& rows);

} // namespace lamina::materials
