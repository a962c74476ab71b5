#include "materials/point_driver.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "materials/kinematics.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>

namespace lamina::materials {

namespace {

/// Deformation gradient of the path at driven strain e and lateral strains l.
Eigen::Matrix3d pathF(DrivePath path, double e, const Eigen::Vector2d& l) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  switch (path) {
  case DrivePath::UniaxialStrain:
    F(0, 0) += e;
    break;
  case DrivePath::Confined:
    F(0, 0) -= e;
    break;
  case DrivePath::Shear:
    F(0, 1) = e;
    break;
  case DrivePath::UniaxialStress:
    F(0, 0) += e;
    F(1, 1) += l[0];
    F(2, 2) += l[1];
    break;
  case DrivePath::BiaxialStress:
    F(0, 0) += e;
    F(1, 1) += e;
    F(2, 2) += l[1];
    break;
  }
  return F;
}

/// A material point: law, state, accumulated rotation-free strain.
class Point {
public:
  Point(const ConstitutiveLaw& law, Kinematics kin)
      : law_(law), kin_(kin), state_(static_cast<std::size_t>(law.stateSize())),
        trial_(state_.size()) {
    law_.initState(state_.data());
  }

  /// Stress at F_{n+1} = F over dt from the committed state (not committed).
  Vector6 trial(const Eigen::Matrix3d& F, double dt, Matrix6* tangent) {
    PointStep step;
    step.dt = dt;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (kin_ == Kinematics::Small) {
      step.eps_n = smallStrain(F_);
      step.eps = smallStrain(F);
      step.J_n = 1 + step.eps_n.head<3>().sum();
      step.J = 1 + step.eps.head<3>().sum();
    } else {
      const FiniteIncrement inc = finiteIncrement(F_, F);
      step.eps_n = eps_hat_;
      step.eps = eps_hat_ + inc.deps;
      step.J_n = inc.J_n;
      step.J = inc.J;
      R = inc.R;
    }
    trial_eps_ = step.eps;
    trial_step_ = step;
    trial_R_ = R;
    Vector6 sigma;
    law_.update(step, state_.data(), trial_.data(), sigma, tangent);
    return kin_ == Kinematics::Small ? sigma : rotateTensor(R, sigma);
  }

  /// The last trial as an observer sees it (state_n: the committed state).
  DriveStep last(int n, double t) const {
    DriveStep s;
    s.n = n;
    s.t = t;
    s.step = trial_step_;
    s.state_n = state_.data();
    s.R = trial_R_;
    return s;
  }

  /// Accepts the last trial at F.
  void commit(const Eigen::Matrix3d& F) {
    state_ = trial_;
    eps_hat_ = trial_eps_;
    F_ = F;
  }

private:
  const ConstitutiveLaw& law_;
  Kinematics kin_;
  std::vector<double> state_, trial_;
  Eigen::Matrix3d F_ = Eigen::Matrix3d::Identity();
  Vector6 eps_hat_ = Vector6::Zero(), trial_eps_ = Vector6::Zero();
  PointStep trial_step_;
  Eigen::Matrix3d trial_R_ = Eigen::Matrix3d::Identity();
};

} // namespace

const char* toString(DrivePath p) {
  return kDrivePathNames.name(p).data(); // the table's names are literals: NUL-terminated
}

void checkRate(double rate, const std::string& option, bool allow_infinite) {
  if (allow_infinite && rate == std::numeric_limits<double>::infinity())
    return;
  if (!(rate >= kMinRate && rate <= kMaxRate))
    throw Error(detail::concat("strain rate ", rate, " /s is outside [", kMinRate, ", ", kMaxRate,
                               "] /s", allow_infinite ? " (or inf)" : ""),
                {"", 0, option});
}

void checkFinalStrain(DrivePath path, double to, const std::string& option) {
  if (!(to > 0) || !std::isfinite(to))
    throw Error(detail::concat("final strain must be positive and finite, got ", to),
                {"", 0, option});
  if (path == DrivePath::Confined && to >= 1)
    throw Error(detail::concat("confined compression to a strain of ", to,
                               " (1 or more) crushes the point to zero volume"),
                {"", 0, option});
}

namespace {

/// Writes "," (unless @p first) and @p x with 17 significant digits.
void csvNumber(std::ostream& os, double x, bool first = false) {
  char buf[32];
  std::snprintf(buf, sizeof buf, first ? "%.17g" : ",%.17g", x);
  os << buf;
}

/// The lateral Newton of the stress paths: the stresses of the free lateral
/// components (uniaxial stress: yy, zz by l_y, l_z; biaxial stress: zz by
/// l_z) to zero, with the tangent's lateral block (d eps_hat / d l = 1 /
/// F_ll at the midpoint). Updates @p l, @p F, @p sigma and @p T.
void lateralNewton(Point& point, const DriveOptions& o, double e, double dt, Eigen::Vector2d& l,
                   Eigen::Matrix3d& F, Vector6& sigma, Matrix6& T) {
  const bool uniaxial = o.path == DrivePath::UniaxialStress;
  // relative to the driven stress of the current iterate (not of the first
  // trial, whose lateral constraint makes it larger)
  const auto converged = [&] {
    const double driven =
        uniaxial ? std::abs(sigma[0]) : std::max(std::abs(sigma[0]), std::abs(sigma[1]));
    const double lateral =
        uniaxial ? std::max(std::abs(sigma[1]), std::abs(sigma[2])) : std::abs(sigma[2]);
    return lateral <= 1e-10 * std::max(driven, 1.0) + 1e-6;
  };
  for (int it = 0; !converged();) {
    LAMINA_CHECK(++it <= 50, toString(o.path), ": lateral stress did not vanish");
    if (uniaxial) {
      Eigen::Matrix2d Tl;
      Tl << T(1, 1) / F(1, 1), T(1, 2) / F(2, 2), T(2, 1) / F(1, 1), T(2, 2) / F(2, 2);
      l -= Tl.lu().solve(Eigen::Vector2d(sigma[1], sigma[2]));
    } else {
      l[1] -= sigma[2] / (T(2, 2) / F(2, 2));
    }
    F = pathF(o.path, e, l);
    sigma = point.trial(F, dt, &T);
  }
}

/// Step @p n of drive(): the trial at the path's strain (with the lateral
/// Newton of the stress paths, updating @p l), reported and committed.
DriveRow driveStep(Point& point, const DriveOptions& o, int n, double dt, Eigen::Vector2d& l,
                   const std::function<void(const DriveStep&)>& observer) {
  const int k = n <= o.steps ? n : 2 * o.steps - n;
  const double e = o.to * k / o.steps;
  Eigen::Matrix3d F = pathF(o.path, e, l);
  Matrix6 T;
  Vector6 sigma = point.trial(F, dt, &T);
  if (o.path == DrivePath::UniaxialStress || o.path == DrivePath::BiaxialStress)
    lateralNewton(point, o, e, dt, l, F, sigma, T);
  DriveRow row;
  row.t = n * dt;
  if (observer)
    observer(point.last(n, row.t));
  point.commit(F);
  row.eps = smallStrain(F);
  row.sigma = sigma;
  return row;
}

} // namespace

std::vector<DriveRow> drive(const ConstitutiveLaw& law, const DriveOptions& o,
                            const std::function<void(const DriveStep&)>& observer) {
  checkRate(o.rate, "--rate");
  checkFinalStrain(o.path, o.to, "--to");
  LAMINA_CHECK(o.steps >= 1, "--steps must be at least 1");
  Point point(law, o.kinematics);
  std::vector<DriveRow> rows{DriveRow{}};
  const double dt = o.to / o.rate / o.steps;
  Eigen::Vector2d l = Eigen::Vector2d::Zero();
  const int total = o.unload ? 2 * o.steps : o.steps;
  for (int n = 1; n <= total; ++n) {
    try {
      rows.push_back(driveStep(point, o, n, dt, l, observer));
    } catch (const Error& e) {
      // the step and its time in front, the law's context (its entry) kept
      throw Error(detail::concat("step ", n, " of ", total, " (t = ", n * dt, " s): ", e.message()),
                  e.context());
    }
  }
  return rows;
}

std::function<void(const DriveStep&)> recordNonlinearDispersion(const ReducedOrderLaw& law,
                                                                std::vector<DispersionRow>& rows) {
  return [&law, &rows](const DriveStep& s) {
    std::vector<double> scratch(static_cast<std::size_t>(law.stateSize()));
    ReducedOrderStepInfo info;
    Vector6 sigma;
    law.updateWithInfo(s.step, s.state_n, scratch.data(), sigma, nullptr, &info);
    const Matrix6 D = law.nonlinearDispersion(info);
    const double lin = law.model().D_lin.cwiseAbs().maxCoeff();
    const double nonlin = D.cwiseAbs().maxCoeff();
    DispersionRow row;
    row.t = s.t;
    row.D = Stiffness(D).rotated(s.R).matrix();
    row.ratio = lin > 0 ? nonlin / lin : (nonlin > 0 ? std::numeric_limits<double>::infinity() : 0);
    rows.push_back(row);
  };
}

void writeDispersionCsv(const std::filesystem::path& path, const std::vector<DispersionRow>& rows) {
  std::ostringstream os;
  os << "t";
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j)
      os << ",D" << i + 1 << j + 1;
  os << ",max_ratio\n";
  for (const DispersionRow& r : rows) {
    csvNumber(os, r.t, true);
    for (int i = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j)
        csvNumber(os, r.D(i, j));
    csvNumber(os, r.ratio);
    os << "\n";
  }
  core::writeFileAtomically(path, os.str());
}

void writeDriveCsv(const std::filesystem::path& path, const std::vector<DriveRow>& rows) {
  std::ostringstream os;
  os << kDriveHeader << "\n";
  for (const DriveRow& r : rows) {
    csvNumber(os, r.t, true);
    for (int i = 0; i < 6; ++i)
      csvNumber(os, r.eps[i]);
    for (int i = 0; i < 6; ++i)
      csvNumber(os, r.sigma[i]);
    os << "\n";
  }
  core::writeFileAtomically(path, os.str());
}

} // namespace lamina::materials
