#include "membrane/loads/blast.hpp"

#include "core/pair_table.hpp"

#include "core/format.hpp"
#include "core/input_file.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lamina::membrane {

namespace {

using core::formatShort;

/// One piece of a fit: valid for lo <= Z <= hi (m/kg^(1/3)).
/// Swisdak form: Y = exp(sum c_i (ln Z)^i).
/// Kingery-Bulmash form: U = k0 + k1 log10 Z, Y = 10^(sum c_i U^i).
struct Piece {
  double lo, hi;
  double k0, k1; // KB only (unused in the Swisdak form)
  std::vector<double> c;
};

/// A fitted parameter: its pieces, in increasing Z.
using Fit = std::vector<Piece>;

double horner(const std::vector<double>& c, double x) {
  double y = 0;
  for (auto it = c.rbegin(); it != c.rend(); ++it)
    y = y * x + *it;
  return y;
}

const Piece& pieceFor(const Fit& fit, double z) {
  for (const auto& p : fit)
    if (z >= p.lo && z <= p.hi)
      return p;
  // Callers clamp Z into validRange(), which every fit covers.
  return z < fit.front().lo ? fit.front() : fit.back();
}

double swisdak(const Fit& fit, double z) {
  return std::exp(horner(pieceFor(fit, z).c, std::log(z)));
}

double kingery(const Fit& fit, double z) {
  const auto& p = pieceFor(fit, z);
  return std::pow(10.0, horner(p.c, p.k0 + p.k1 * std::log10(z)));
}

/// The six fits of one burst type, in the units of the source (kPa, ms/kg^(1/3),
/// kPa ms/kg^(1/3)).
struct FitSet {
  Fit arrival, incident_pressure, reflected_pressure, duration, incident_impulse, reflected_impulse;
};

// Swisdak (1994), metric table, hemispherical TNT surface burst.
const FitSet& swisdakHemispherical() {
  static const FitSet s{
      // arrival time, ms/kg^(1/3)
      {{0.06, 1.50, 0, 0, {-0.7604, 1.8058, 0.1257, -0.0437, -0.0310, -0.00669}},
       {1.50, 40.0, 0, 0, {-0.7137, 1.5732, 0.5561, -0.4213, 0.1054, -0.00929}}},
      // incident overpressure, kPa
      {{0.2, 2.9, 0, 0, {7.2106, -2.1069, -0.3229, 0.1117, 0.0685}},
       {2.9, 23.8, 0, 0, {7.5938, -3.0523, 0.40977, 0.0261, -0.01267}},
       {23.8, 198.5, 0, 0, {6.0536, -1.4066}}},
      // normally reflected overpressure, kPa
      {{0.06, 2.00, 0, 0, {9.006, -2.6893, -0.6295, 0.1011, 0.29255, 0.13505, 0.019736}},
       {2.00, 40.0, 0, 0, {8.8396, -1.733, -2.64, 2.293, -0.8232, 0.14247, -0.0099}}},
      // positive-phase duration, ms/kg^(1/3)
      {{0.2, 1.02, 0, 0, {0.5426, 3.2299, -1.5931, -5.9667, -4.0815, -0.9149}},
       {1.02, 2.8, 0, 0, {0.5440, 2.7082, -9.7354, 14.3425, -9.7791, 2.8535}},
       {2.8, 40.0, 0, 0, {-2.4608, 7.1639, -5.6215, 2.2711, -0.44994, 0.03486}}},
      // incident impulse, kPa ms/kg^(1/3)
      {{0.2, 0.96, 0, 0, {5.522, 1.117, 0.6, -0.292, -0.087}},
       {0.96, 2.38, 0, 0, {5.465, -0.308, -1.464, 1.362, -0.432}},
       {2.38, 33.7, 0, 0, {5.2749, -0.4677, -0.2499, 0.0588, -0.00554}},
       {33.7, 158.7, 0, 0, {5.9825, -1.062}}},
      // reflected impulse, kPa ms/kg^(1/3)
      {{0.06, 40.0, 0, 0, {6.7853, -1.3466, 0.101, -0.01123}}},
  };
  return s;
}

// Kingery & Bulmash (1984), metric, spherical free-air burst.
const FitSet& kingeryBulmashSpherical() {
  static const FitSet s{
      // arrival time, ms/kg^(1/3)
      {{0.0531,
        40.0,
        -0.253273111999,
        1.37407043777,
        {0.0720707787637, 1.36456871214, -0.0570035692784, -0.182832224796, 0.0118851436014,
         0.0432648687627, -0.0007997367834, -0.00436073555033}}},
      // incident overpressure, kPa
      {{0.0531,
        40.0,
        -0.214362789151,
        1.35034249993,
        {2.611368669, -1.690128014, 0.00804973591, 0.336743114, -0.00516226351, -0.0809228619,
         -0.00478507266, 0.00793030472, 0.0007684469}}},
      // normally reflected overpressure, kPa
      {{0.0531,
        40.0,
        -0.214362789151,
        1.35034249993,
        {3.22958031387, -2.21400538997, 0.035119031446, 0.657599992109, 0.0141818951887,
         -0.243076636231, -0.0158699803158, 0.0492741184234, 0.00227639644004, -0.00397126276058}}},
      // positive-phase duration, ms/kg^(1/3)
      {{0.147,
        0.888,
        2.26367268496,
        5.11588554305,
        {-0.686608550419, 0.164953518069, 0.127788499497, 0.00291430135946, 0.00187957449227,
         0.0173413962543, 0.00269739758043, -0.00361976502798, -0.00100926577934}},
       {0.888,
        2.28,
        -1.33361206714,
        9.2996288611,
        {0.23031841078, -0.0297944268969, 0.0306329542941, 0.0183405574074, -0.0173964666286,
         -0.00106321963576, 0.0056206003128, 0.0001618217499, -0.0006860188944}},
       {2.28,
        40.0,
        -3.13005805346,
        3.1524725364,
        {0.621036276475, 0.0967031995552, -0.00801302059667, 0.00482705779732, 0.00187587272287,
         -0.00246738509321, -0.000841116668, 0.0006193291052}}},
      // incident impulse, kPa ms/kg^(1/3)
      {{0.0531,
        0.792,
        2.34723921354,
        3.24299066475,
        {2.38830516757, -0.443749377691, 0.168825414684, 0.0348138030308, -0.010435192824}},
       {0.792,
        40.0,
        -1.75305660315,
        2.30629231803,
        {1.55197227115, -0.40463292088, -0.0142721946082, 0.00912366316617, -0.0006750681404,
         -0.00800863718901, 0.00314819515931, 0.00152044783382, -0.0007470265899}}},
      // reflected impulse, kPa ms/kg^(1/3)
      {{0.0531,
        40.0,
        -0.204004455231,
        1.37882996018,
        {2.55875660396, -0.903118886091, 0.101771877942, -0.0242139751146}}},
  };
  return s;
}

bool positiveFinite(double x) {
  return std::isfinite(x) && x > 0;
}

} // namespace

Burst parseBurst(const std::string& name, const ErrorContext& where) {
  return kBurstNames.parseOrThrow(name, "burst", where);
}

const char* burstName(Burst burst) {
  return kBurstNames.name(burst).data(); // the table's names are literals: NUL-terminated
}

ScaledRange validRange(Burst burst) {
  // The intersection of the six parameters' ranges in each source.
  return burst == Burst::Hemispherical ? ScaledRange{0.2, 40.0} : ScaledRange{0.147, 40.0};
}

BlastParameters kingeryBulmash(double tnt_mass, double distance, Burst burst, OutOfRange policy) {
  LAMINA_CHECK(positiveFinite(tnt_mass),
               "blast: the TNT-equivalent charge must be positive and finite, got ",
               formatShort(tnt_mass), " kg");
  LAMINA_CHECK(positiveFinite(distance),
               "blast: the distance from the charge must be positive and finite, got ",
               formatShort(distance), " m");
  BlastParameters p;
  p.charge = tnt_mass;
  p.distance = distance;
  const double cube_root = std::cbrt(tnt_mass);
  p.scaled_distance = distance / cube_root;
  const ScaledRange range = validRange(burst);
  double z = p.scaled_distance;
  if (z < range.min || z > range.max) {
    const std::string what = "blast: scaled distance Z = " + formatShort(z, 4) +
                             " m/kg^(1/3) (R = " + formatShort(distance, 4) +
                             " m, W = " + formatShort(tnt_mass, 4) + " kg TNT) is outside [" +
                             formatShort(range.min) + ", " + formatShort(range.max) +
                             "], the validity range of the " + burstName(burst) + " burst fits";
    if (policy == OutOfRange::Refuse)
      throw Error(what);
    z = std::clamp(z, range.min, range.max);
    p.clamped = true;
  }
  const bool hemi = burst == Burst::Hemispherical;
  const FitSet& f = hemi ? swisdakHemispherical() : kingeryBulmashSpherical();
  const auto eval = [&](const Fit& fit) { return hemi ? swisdak(fit, z) : kingery(fit, z); };
  constexpr double kPa = 1e3, ms = 1e-3;
  p.arrival_time = eval(f.arrival) * cube_root * ms;
  p.incident_pressure = eval(f.incident_pressure) * kPa;
  p.reflected_pressure = eval(f.reflected_pressure) * kPa;
  p.positive_duration = eval(f.duration) * cube_root * ms;
  p.incident_impulse = eval(f.incident_impulse) * cube_root * kPa * ms;
  p.reflected_impulse = eval(f.reflected_impulse) * cube_root * kPa * ms;
  return p;
}

nlohmann::json blastToJson(const BlastParameters& p, Burst burst) {
  const ScaledRange range = validRange(burst);
  const BlastHistory h = blastHistory(p);
  return {{"burst", burstName(burst)},
          {"charge", p.charge},
          {"distance", p.distance},
          {"scaled_distance", p.scaled_distance},
          {"scaled_distance_range", {range.min, range.max}},
          {"clamped", p.clamped},
          {"arrival_time", p.arrival_time},
          {"incident_pressure", p.incident_pressure},
          {"reflected_pressure", p.reflected_pressure},
          {"positive_duration", p.positive_duration},
          {"incident_impulse", p.incident_impulse},
          {"reflected_impulse", p.reflected_impulse},
          {"incident_decay", h.incident.decay},
          {"reflected_decay", h.reflected.decay}};
}

std::string blastTable(const BlastParameters& p, Burst burst) {
  const ScaledRange range = validRange(burst);
  const BlastHistory h = blastHistory(p);
  std::ostringstream os;
  const auto row = [&](const std::string& name, const std::string& value) {
    os << "  " << name << std::string(name.size() < 28 ? 28 - name.size() : 1, ' ') << value
       << "\n";
  };
  os << burstName(burst) << " burst, " << formatShort(p.charge) << " kg TNT at "
     << formatShort(p.distance) << " m ("
     << (burst == Burst::Hemispherical ? "Swisdak 1994" : "Kingery-Bulmash 1984") << ")\n";
  row("scaled distance Z", formatShort(p.scaled_distance, 5) + " m/kg^(1/3)  (valid " +
                               formatShort(range.min) + " .. " + formatShort(range.max) +
                               (p.clamped ? ", CLAMPED)" : ")"));
  row("arrival time", formatShort(p.arrival_time * 1e3, 5) + " ms");
  row("incident overpressure", formatShort(p.incident_pressure * 1e-3, 5) + " kPa");
  row("reflected overpressure", formatShort(p.reflected_pressure * 1e-3, 5) + " kPa");
  row("positive duration", formatShort(p.positive_duration * 1e3, 5) + " ms");
  row("incident impulse", formatShort(p.incident_impulse, 5) + " Pa s");
  row("reflected impulse", formatShort(p.reflected_impulse, 5) + " Pa s");
  row("Friedlander decay (inc/ref)",
      formatShort(h.incident.decay, 5) + " / " + formatShort(h.reflected.decay, 5));
  return os.str();
}

double friedlanderImpulseFraction(double b) {
  if (std::abs(b) < 1e-4) // series of (b - 1 + e^-b)/b^2: error < b^3/120 < 1e-14
    return 0.5 - b / 6.0 + b * b / 24.0;
  return (b - 1.0 + std::exp(-b)) / (b * b);
}

double friedlanderDecay(double peak, double duration, double impulse) {
  LAMINA_CHECK(positiveFinite(peak) && positiveFinite(duration) && positiveFinite(impulse),
               "Friedlander pulse: peak (", formatShort(peak), " Pa), duration (",
               formatShort(duration), " s) and impulse (", formatShort(impulse),
               " Pa s) must be positive and finite");
  const double ratio = impulse / (peak * duration);
  // The fraction falls monotonically from +inf (b -> -inf) to 0 (b -> +inf):
  // bracket the root, then bisect (60 halvings reach double precision).
  double lo = -1.0, hi = 1.0;
  while (friedlanderImpulseFraction(lo) < ratio) {
    lo *= 2.0;
    LAMINA_CHECK(lo > -1e3, "Friedlander pulse: impulse ", formatShort(impulse),
                 " Pa s exceeds what a pulse of peak ", formatShort(peak), " Pa and duration ",
                 formatShort(duration), " s can carry");
  }
  while (friedlanderImpulseFraction(hi) > ratio) {
    hi *= 2.0;
    LAMINA_CHECK(hi < 1e9, "Friedlander pulse: impulse ", formatShort(impulse),
                 " Pa s is too small for peak ", formatShort(peak), " Pa and duration ",
                 formatShort(duration), " s");
  }
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (friedlanderImpulseFraction(mid) > ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double FriedlanderPulse::pressure(double tau) const {
  if (tau < 0 || tau > duration)
    return 0.0;
  const double x = tau / duration;
  return peak * (1.0 - x) * std::exp(-decay * x);
}

double FriedlanderPulse::impulse() const {
  return peak * duration * friedlanderImpulseFraction(decay);
}

namespace {
/// int_0^x (1 - s) exp(-b s) ds = x E1(b x) - x^2 E2(b x) with
/// E1(y) = (1 - e^-y) / y and E2(y) = (1 - e^-y (1 + y)) / y^2; for |y| < 0.1
/// their series sum_k (-y)^k / (k+1)! and sum_k (-y)^k (k+1) / (k+2)!
/// (18 terms: the next is below 1e-18 of the sum) avoid the cancellation.
double friedlanderPrimitive(double b, double x) {
  const double y = b * x;
  double e1 = 0, e2 = 0;
  if (std::abs(y) < 0.1) {
    double term = 1; // (-y)^k / k!
    for (int k = 0; k < 18; ++k) {
      e1 += term / (k + 1);
      e2 += term / (k + 2);
      term *= -y / (k + 1);
    }
  } else {
    const double m = -std::expm1(-y); // 1 - e^-y
    e1 = m / y;
    e2 = (m - y * std::exp(-y)) / (y * y);
  }
  return x * e1 - x * x * e2;
}
} // namespace

double FriedlanderPulse::impulseBetween(double tau0, double tau1) const {
  const double a = std::max(tau0, 0.0), b = std::min(tau1, duration);
  if (!(b > a))
    return 0.0;
  return peak * duration *
         (friedlanderPrimitive(decay, b / duration) - friedlanderPrimitive(decay, a / duration));
}

double combineIncidentReflected(double incident, double reflected, double cos_angle) {
  if (cos_angle < 0)
    return incident;
  const double c = std::min(cos_angle, 1.0);
  return reflected * c * c + incident * (1.0 + c * c - 2.0 * c);
}

double BlastHistory::pressure(double t, double cos_angle) const {
  const double tau = t - arrival;
  return combineIncidentReflected(incident.pressure(tau), reflected.pressure(tau), cos_angle);
}

double BlastHistory::impulseBetween(double t0, double t1, double cos_angle) const {
  return combineIncidentReflected(incident.impulseBetween(t0 - arrival, t1 - arrival),
                                  reflected.impulseBetween(t0 - arrival, t1 - arrival), cos_angle);
}

BlastHistory blastHistory(const BlastParameters& p) {
  BlastHistory h;
  h.arrival = p.arrival_time;
  const double td = p.positive_duration;
  h.incident = {p.incident_pressure, td,
                friedlanderDecay(p.incident_pressure, td, p.incident_impulse)};
  h.reflected = {p.reflected_pressure, td,
                 friedlanderDecay(p.reflected_pressure, td, p.reflected_impulse)};
  return h;
}

BlastParameters BlastCharge::parametersAt(const Eigen::Vector3d& point) const {
  LAMINA_CHECK(positiveFinite(tnt_equivalence),
               "blast: the TNT-equivalence factor must be positive, got ",
               formatShort(tnt_equivalence));
  return kingeryBulmash(mass * tnt_equivalence, (point - position).norm(), burst, policy);
}

BlastHistory BlastCharge::historyAt(const Eigen::Vector3d& point) const {
  return blastHistory(parametersAt(point));
}

PressureTable::PressureTable(std::vector<double> times, std::vector<double> pressures,
                             const ErrorContext& where)
    : times_(std::move(times)), pressures_(std::move(pressures)) {
  if (times_.size() != pressures_.size() || times_.size() < 2)
    throw Error("a pressure history needs at least two (time, pressure) rows of equal length",
                where);
  for (std::size_t i = 0; i < times_.size(); ++i) {
    if (!std::isfinite(times_[i]) || !std::isfinite(pressures_[i]))
      throw Error("pressure history row " + std::to_string(i + 1) + " is not finite", where);
    if (i > 0 && !(times_[i] > times_[i - 1]))
      throw Error("pressure history times must increase strictly: row " + std::to_string(i + 1) +
                      " has t = " + formatShort(times_[i]) +
                      " after t = " + formatShort(times_[i - 1]),
                  where);
  }
  cumulative_.assign(times_.size(), 0.0);
  for (std::size_t i = 1; i < times_.size(); ++i)
    cumulative_[i] = cumulative_[i - 1] +
                     0.5 * (pressures_[i] + pressures_[i - 1]) * (times_[i] - times_[i - 1]);
}

PressureTable PressureTable::readCsv(const std::string& path) {
  const std::string text = core::readWholeFile(path, core::kMaxTableBytes, "pressure table");
  std::vector<double> t, p;
  for (const core::PairRow& r : core::readPairRows(text, path, "", "'time,pressure' (s, Pa)")) {
    t.push_back(r.first);
    p.push_back(r.second);
  }
  return PressureTable(std::move(t), std::move(p), {path, 0, ""});
}

double PressureTable::pressure(double t) const {
  if (t < times_.front() || t > times_.back())
    return 0.0;
  const auto hi = std::upper_bound(times_.begin(), times_.end(), t);
  if (hi == times_.end())
    return pressures_.back();
  const std::size_t j = static_cast<std::size_t>(hi - times_.begin());
  const double w = (t - times_[j - 1]) / (times_[j] - times_[j - 1]);
  return (1.0 - w) * pressures_[j - 1] + w * pressures_[j];
}

double PressureTable::integralTo(double t) const {
  const auto hi = std::upper_bound(times_.begin(), times_.end(), t);
  if (hi == times_.end())
    return cumulative_.back();
  const std::size_t j = static_cast<std::size_t>(hi - times_.begin()); // >= 1 in the range
  return cumulative_[j - 1] + 0.5 * (t - times_[j - 1]) * (pressures_[j - 1] + pressure(t));
}

double PressureTable::impulseBetween(double t0, double t1) const {
  const double a = std::max(t0, times_.front()), b = std::min(t1, times_.back());
  return b > a ? integralTo(b) - integralTo(a) : 0.0;
}

double PressureTable::impulse() const {
  double s = 0;
  for (std::size_t i = 1; i < times_.size(); ++i)
    s += 0.5 * (pressures_[i] + pressures_[i - 1]) * (times_[i] - times_[i - 1]);
  return s;
}

} // namespace lamina::membrane
