#pragma once
/// @file blast.hpp
/// @brief Air-blast loading: Kingery-Bulmash blast parameters, the Friedlander
/// pulse whose decay matches the impulse, the angle-of-incidence combination
/// of incident and reflected pressure, and a user pressure history (CSV).
///
/// Sources (formulas and coefficients, see docs/membrane-blast.md "Blast loads"):
/// - Hemispherical surface burst: M. M. Swisdak, "Simplified Kingery Airblast
///   Calculations", NSWC Indian Head, 1994: Y = exp(A + B ln Z + C ln^2 Z + ...)
///   with Z in m/kg^(1/3), pressures in kPa, times in ms/kg^(1/3), impulses in
///   kPa ms/kg^(1/3).
/// - Spherical free-air burst: C. N. Kingery and G. Bulmash, "Airblast
///   Parameters from TNT Spherical Air Burst and Hemispherical Surface Burst",
///   ARBRL-TR-02555, 1984: log10 Y = sum C_i U^i, U = K0 + K1 log10 Z (the
///   original form; Swisdak's report simplifies the surface burst only).
/// - Angle of incidence: G. Randers-Pehrson and K. A. Bannister, "Airblast
///   Loading Model for DYNA2D and DYNA3D", ARL-TR-1310, 1997 (the model of
///   LS-DYNA's *LOAD_BLAST_ENHANCED).

#include "core/enum_names.hpp"
#include "core/error.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lamina::membrane {

/// Charge configuration of the Kingery-Bulmash curves.
enum class Burst {
  Hemispherical, ///< hemispherical charge on the ground (surface burst)
  Spherical,     ///< spherical charge in free air, far from any surface
};

/// The burst names of case files (blast.burst) and of the CLI (--burst), the
/// one table both read: "hemispherical", "spherical".
inline constexpr auto kBurstNames = core::enumNames<Burst>(
    {{"hemispherical", Burst::Hemispherical}, {"spherical", Burst::Spherical}});

/// Parses a name of kBurstNames; otherwise an Error naming @p where and the names.
Burst parseBurst(const std::string& name, const ErrorContext& where = {});

/// @return the name of @p burst in kBurstNames
const char* burstName(Burst burst);

/// Scaled-distance interval Z = R / W^(1/3) (m/kg^(1/3)) in which all six
/// fitted parameters of a burst type are defined.
struct ScaledRange {
  double min = 0; ///< lower end, m/kg^(1/3)
  double max = 0; ///< upper end, m/kg^(1/3)
};

/// @return the validity interval of the fits for @p burst:
/// hemispherical [0.2, 40], spherical [0.147, 40] m/kg^(1/3)
ScaledRange validRange(Burst burst);

/// What to do with a scaled distance outside validRange().
enum class OutOfRange {
  Refuse, ///< throw an Error naming Z, R, W and the interval
  Clamp,  ///< evaluate the fits at the nearest end of the interval (flagged)
};

/// Blast parameters at one distance, SI units (peak values are overpressures).
struct BlastParameters {
  double charge = 0;             ///< TNT-equivalent mass W, kg
  double distance = 0;           ///< distance R from the charge centre, m
  double scaled_distance = 0;    ///< Z = R / W^(1/3), m/kg^(1/3)
  bool clamped = false;          ///< Z was outside the range and clamped
  double arrival_time = 0;       ///< shock arrival after detonation, s
  double incident_pressure = 0;  ///< peak incident (side-on) overpressure, Pa
  double reflected_pressure = 0; ///< peak normally reflected overpressure, Pa
  double positive_duration = 0;  ///< positive-phase duration, s
  double incident_impulse = 0;   ///< incident positive-phase impulse, Pa s
  double reflected_impulse = 0;  ///< normally reflected positive-phase impulse, Pa s
};

/// Kingery-Bulmash blast parameters of @p tnt_mass kg TNT at @p distance m.
/// @param policy refuse (Error naming the value) or clamp outside validRange()
BlastParameters kingeryBulmash(double tnt_mass, double distance, Burst burst,
                               OutOfRange policy = OutOfRange::Refuse);

/// The parameters as JSON with SI keys: arrival_time, incident_pressure,
/// reflected_pressure, positive_duration, incident_impulse, reflected_impulse
/// (the interface of `membrane blast --json`), plus the inputs, the burst,
/// the validity range and the Friedlander decay constants.
nlohmann::json blastToJson(const BlastParameters& p, Burst burst);

/// The parameters as a human-readable table (engineering units beside SI).
std::string blastTable(const BlastParameters& p, Burst burst);

/// Fraction of P td that a Friedlander pulse of decay @p b carries:
/// int_0^1 (1 - x) exp(-b x) dx = (b - 1 + exp(-b)) / b^2 (1/2 at b = 0).
double friedlanderImpulseFraction(double b);

/// The decay constant b with P td friedlanderImpulseFraction(b) = @p impulse
/// (unique: the fraction decreases monotonically in b). Error unless all three
/// inputs are positive and finite.
double friedlanderDecay(double peak, double duration, double impulse);

/// Positive phase of the Friedlander waveform
/// p(tau) = P (1 - tau/td) exp(-b tau/td) for 0 <= tau <= td, 0 otherwise.
struct FriedlanderPulse {
  double peak = 0;     ///< P, Pa
  double duration = 0; ///< td, s
  double decay = 0;    ///< b, dimensionless

  /// @return the overpressure @p tau seconds after arrival, Pa
  double pressure(double tau) const;
  /// @return int_0^td p dtau = P td friedlanderImpulseFraction(b), Pa s
  double impulse() const;
  /// @return int p dtau over [@p tau0, @p tau1] (s after arrival; the
  /// pressure is 0 outside [0, td]), in closed form, Pa s
  double impulseBetween(double tau0, double tau1) const;
};

/// Randers-Pehrson & Bannister (1997) combination for a surface whose normal
/// makes the angle a with the direction to the charge:
/// P = Pr cos^2 a + Pi (1 + cos^2 a - 2 cos a) for cos a >= 0, P = Pi otherwise.
double combineIncidentReflected(double incident, double reflected, double cos_angle);

/// Pressure history at one point: both pulses share arrival and duration.
struct BlastHistory {
  double arrival = 0;         ///< s after detonation
  FriedlanderPulse incident;  ///< side-on pulse (decay matches the incident impulse)
  FriedlanderPulse reflected; ///< normally reflected pulse (matches the reflected impulse)

  /// @return the overpressure at time @p t (s after detonation) on a face
  /// whose normal makes cos a = @p cos_angle with the direction to the charge
  double pressure(double t, double cos_angle) const;
  /// @return int pressure(t, @p cos_angle) dt over [@p t0, @p t1] (s after
  /// detonation), Pa s: the combination is linear in the two pulses
  double impulseBetween(double t0, double t1, double cos_angle) const;
};

/// Builds the history of @p p (decay constants solved from the impulses).
BlastHistory blastHistory(const BlastParameters& p);

/// A charge at a point: TNT-equivalent mass, burst type, range policy.
struct BlastCharge {
  Eigen::Vector3d position = Eigen::Vector3d::Zero(); ///< charge centre, m
  double mass = 0;                                    ///< explosive mass, kg
  double tnt_equivalence = 1.0;           ///< TNT-equivalence factor (W = factor * mass)
  Burst burst = Burst::Hemispherical;     ///< curve set
  OutOfRange policy = OutOfRange::Refuse; ///< outside the fits' range

  /// @return the Kingery-Bulmash parameters at @p point
  BlastParameters parametersAt(const Eigen::Vector3d& point) const;
  /// @return the pressure history at @p point
  BlastHistory historyAt(const Eigen::Vector3d& point) const;
};

/// A user pressure history p(t): linear between rows, 0 before the first
/// and after the last row.
class PressureTable {
public:
  /// @param times strictly increasing, finite, s
  /// @param pressures finite, Pa, same length (>= 2)
  /// @param where file (and key) named in errors
  PressureTable(std::vector<double> times, std::vector<double> pressures,
                const ErrorContext& where = {});

  /// Reads "time,pressure" rows (SI) from a CSV file; a first line that is
  /// not numeric is a header; '#' starts a comment. Errors name file and line.
  static PressureTable readCsv(const std::string& path);

  /// @return p(@p t), Pa
  double pressure(double t) const;
  /// @return the integral of p over the table (trapezoids: exact for the
  /// piecewise-linear history), Pa s
  double impulse() const;
  /// @return the integral of p over [@p t0, @p t1] (exact for the
  /// piecewise-linear history, 0 outside the table), Pa s
  double impulseBetween(double t0, double t1) const;
  /// @return the time rows, s
  const std::vector<double>& times() const { return times_; }

private:
  /// @return int p over [times_.front(), @p t] for t in the table's range
  double integralTo(double t) const;
  std::vector<double> times_;
  std::vector<double> pressures_;
  std::vector<double> cumulative_; ///< int p over [times_.front(), times_[i]], Pa s
};

} // namespace lamina::membrane
