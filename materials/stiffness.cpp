#include "materials/stiffness.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"

#include <cmath>
#include <ostream>

namespace lamina::materials {

Matrix6 readMatrix6(const core::TableReader& t, std::string_view key, const std::string& unit) {
  const auto rows = t.getMatrix(key);
  const std::string shape = "expected 6 rows of 6 numbers (" + unit + ", lamina order)";
  if (rows.size() != 6)
    t.fail(key, shape);
  Matrix6 c;
  for (int i = 0; i < 6; ++i) {
    const auto& row = rows[static_cast<std::size_t>(i)];
    if (row.size() != 6)
      t.fail(key, shape);
    for (int j = 0; j < 6; ++j)
      c(i, j) = row[static_cast<std::size_t>(j)];
  }
  return c;
}

void writeMatrix6(std::ostream& os, std::string_view key, const Matrix6& c) {
  os << key << " = [\n";
  for (int i = 0; i < 6; ++i) {
    os << "  [";
    for (int j = 0; j < 6; ++j)
      os << (j ? ", " : "") << core::formatExact(c(i, j));
    os << "],\n";
  }
  os << "]\n";
}

Stiffness Stiffness::isotropic(double E, double nu) {
  LAMINA_CHECK(E > 0 && std::isfinite(E), "Young's modulus must be positive, got ", E);
  LAMINA_CHECK(nu > -1.0 && nu < 0.5, "Poisson ratio must lie in (-1, 0.5), got ", nu);
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
  return fromLame(lambda, mu);
}

Stiffness Stiffness::fromLame(double lambda, double mu) {
  LAMINA_CHECK(mu > 0 && 3 * lambda + 2 * mu > 0,
               "Lame constants must give mu > 0 and a positive bulk modulus, got lambda = ", lambda,
               ", mu = ", mu);
  Matrix6 c = Matrix6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      c(i, j) = lambda;
    c(i, i) = lambda + 2 * mu;
    c(3 + i, 3 + i) = mu; // engineering shear strain: tau = mu * gamma
  }
  return Stiffness(c);
}

Stiffness Stiffness::fromUpperTriangle(const std::array<double, 21>& v) {
  Matrix6 c;
  int k = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) {
      c(i, j) = v[static_cast<std::size_t>(k++)];
      c(j, i) = c(i, j);
    }
  return Stiffness(c);
}

std::array<double, 21> Stiffness::upperTriangle() const {
  std::array<double, 21> v{};
  int k = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j)
      v[static_cast<std::size_t>(k++)] = c_(i, j);
  return v;
}

double Stiffness::asymmetry() const {
  const double scale = c_.cwiseAbs().maxCoeff();
  return scale > 0 ? (c_ - c_.transpose()).cwiseAbs().maxCoeff() / scale : 0.0;
}

Stiffness Stiffness::symmetrized() const {
  return Stiffness(0.5 * (c_ + c_.transpose()));
}

double Stiffness::smallestEigenvalue() const {
  Eigen::SelfAdjointEigenSolver<Matrix6> es(0.5 * (c_ + c_.transpose()), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(0);
}

namespace {
/// The fast path of validate: all eigenvalues are positive and the largest
/// is at most the trace, so a Cholesky factorisation of C - 1e-12 tr(C) I
/// proves lo > 1e-12 tr(C) >= 1e-12 hi.
bool cholesky(const Matrix6& c) {
  const double tr = c.trace();
  return tr > 0 && (c - 1e-12 * tr * Matrix6::Identity()).llt().info() == Eigen::Success;
}
} // namespace

bool Stiffness::valid() const {
  if (!c_.allFinite() || asymmetry() > 1e-10)
    return false;
  if (cholesky(c_))
    return true;
  Eigen::SelfAdjointEigenSolver<Matrix6> es(c_, Eigen::EigenvaluesOnly);
  const double lo = es.eigenvalues()(0), hi = es.eigenvalues()(5);
  return hi > 0 && lo > 1e-12 * hi;
}

void Stiffness::validate(const std::string& name) const {
  const ErrorContext ctx{"", 0, name};
  if (!c_.allFinite())
    throw Error("stiffness has NaN or infinite entries", ctx);
  if (asymmetry() > 1e-10)
    throw Error("stiffness is not symmetric (max |C - C^T| / max |C| = " +
                    core::formatShort(asymmetry(), 3) + ")",
                ctx);
  // Fast path (a homogenization validates one stiffness per composite voxel,
  // tens of thousands): cholesky(). Otherwise the eigenvalues decide.
  if (cholesky(c_))
    return;
  Eigen::SelfAdjointEigenSolver<Matrix6> es(c_, Eigen::EigenvaluesOnly);
  const double lo = es.eigenvalues()(0), hi = es.eigenvalues()(5);
  if (!(hi > 0) || lo <= 1e-12 * hi)
    throw Error("stiffness is not positive definite (smallest eigenvalue " + std::to_string(lo) +
                    " Pa, largest " + std::to_string(hi) + " Pa)",
                ctx);
}

Matrix6 Stiffness::compliance() const {
  return c_.inverse();
}

EngineeringConstants Stiffness::engineering() const {
  const Matrix6 s = compliance();
  EngineeringConstants e{};
  e.E1 = 1 / s(0, 0);
  e.E2 = 1 / s(1, 1);
  e.E3 = 1 / s(2, 2);
  e.G12 = 1 / s(3, 3);
  e.G23 = 1 / s(4, 4);
  e.G13 = 1 / s(5, 5);
  e.nu12 = -s(1, 0) / s(0, 0);
  e.nu13 = -s(2, 0) / s(0, 0);
  e.nu23 = -s(2, 1) / s(1, 1);
  e.nu21 = -s(0, 1) / s(1, 1);
  e.nu31 = -s(0, 2) / s(2, 2);
  e.nu32 = -s(1, 2) / s(2, 2);
  return e;
}

Stiffness Stiffness::rotated(const Eigen::Matrix3d& R) const {
  // Bond stress transformation in lamina order: sigma'_ij = R_ik R_jl sigma_kl
  // reads sigma' = T sigma with T(a, b) = R_ik R_jl (+ R_il R_jk for a shear
  // column b = (k, l), k != l); energy invariance gives C' = T C T^T. T holds
  // only products of entries of R (no sqrt(2) scaling as in Mandel form), so
  // an exact R (multiples of 90 degrees) gives an exact signed permutation.
  Matrix6 t;
  for (int a = 0; a < 6; ++a) {
    const auto [i, j] = kLaminaPairs[static_cast<std::size_t>(a)];
    for (int b = 0; b < 6; ++b) {
      const auto [k, l] = kLaminaPairs[static_cast<std::size_t>(b)];
      t(a, b) = k == l ? R(i, k) * R(j, l) : R(i, k) * R(j, l) + R(i, l) * R(j, k);
    }
  }
  return Stiffness(t * c_ * t.transpose());
}

Eigen::Matrix3d axisRotation(int axis, double radians) {
  return Eigen::AngleAxisd(radians, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

Eigen::Matrix3d axisRotationDegrees(int axis, double degrees) {
  // Multiples of 90 degrees get exact cosines and sines, so that [0/90]
  // layups and 90-degree symmetry checks carry no 1e-16 residue. The angle
  // is first reduced to (-360, 360) (fmod is exact), so that the quarter
  // turns fit an int whatever the angle (a ply angle of 1e20 degrees
  // overflowed the cast); a NaN or infinite angle falls through to a NaN
  // rotation, which the readers refuse earlier.
  const double quarterTurns = std::fmod(degrees, 360.0) / 90.0;
  if (quarterTurns == std::round(quarterTurns)) {
    const int k = ((static_cast<int>(quarterTurns) % 4) + 4) % 4;
    const double c[4] = {1, 0, -1, 0}, s[4] = {0, 1, 0, -1};
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    r(a, a) = c[k];
    r(a, b) = -s[k];
    r(b, a) = s[k];
    r(b, b) = c[k];
    return r;
  }
  return axisRotation(axis, degrees * M_PI / 180.0);
}

Stiffness Stiffness::rotatedAboutZ(double radians) const {
  return rotated(axisRotation(2, radians));
}
Stiffness Stiffness::rotatedAboutX(double radians) const {
  return rotated(axisRotation(0, radians));
}
Stiffness Stiffness::rotatedAboutY(double radians) const {
  return rotated(axisRotation(1, radians));
}

// Averages in engineering (Voigt-type) notation: indices 0-2 normal, 3-5 shear,
// which holds in lamina order as in standard Voigt order.
double voigtBulk(const Stiffness& c) {
  const Matrix6& m = c.matrix();
  return ((m(0, 0) + m(1, 1) + m(2, 2)) + 2 * (m(0, 1) + m(1, 2) + m(0, 2))) / 9.0;
}

double voigtShear(const Stiffness& c) {
  const Matrix6& m = c.matrix();
  return ((m(0, 0) + m(1, 1) + m(2, 2)) - (m(0, 1) + m(1, 2) + m(0, 2)) +
          3 * (m(3, 3) + m(4, 4) + m(5, 5))) /
         15.0;
}

namespace {
double reussBulkOf(const Matrix6& s) {
  return 1.0 / ((s(0, 0) + s(1, 1) + s(2, 2)) + 2 * (s(0, 1) + s(1, 2) + s(0, 2)));
}
double reussShearOf(const Matrix6& s) {
  return 15.0 / (4 * (s(0, 0) + s(1, 1) + s(2, 2)) - 4 * (s(0, 1) + s(1, 2) + s(0, 2)) +
                 3 * (s(3, 3) + s(4, 4) + s(5, 5)));
}
} // namespace

double reussBulk(const Stiffness& c) {
  return reussBulkOf(c.compliance());
}

double reussShear(const Stiffness& c) {
  return reussShearOf(c.compliance());
}

void reussModuli(const Stiffness& c, double& bulk, double& shear) {
  const Matrix6 s = c.compliance();
  bulk = reussBulkOf(s);
  shear = reussShearOf(s);
}

double anisotropyIndex(const Stiffness& c) {
  return 5 * voigtShear(c) / reussShear(c) + voigtBulk(c) / reussBulk(c) - 6;
}

} // namespace lamina::materials
