#include "materials/gvbo_law.hpp"

#include "core/error.hpp"
#include "materials/plane_stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lamina::materials {

namespace {

/// a : b for symmetric tensors stored as [xx, yy, zz, xy, yz, xz] (tensor components).
double contract(const Vector6& a, const Vector6& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

/// Deviator of a tensor stored as above.
Vector6 deviator(const Vector6& a) {
  Vector6 d = a;
  const double m = (a[0] + a[1] + a[2]) / 3;
  d[0] -= m;
  d[1] -= m;
  d[2] -= m;
  return d;
}

const double kSqrt23 = std::sqrt(2.0 / 3.0);

/// The scalar problem of one step: every quantity as a function of Gamma,
/// with its derivative (chain rule written out per line).
struct Scalars {
  double Gamma;     // the overstress invariant they are evaluated at
  double c, dc;     // psi / E
  double phi, dphi; // dt / (E k)
  double k;         // viscosity
  double A;         // isotropic stress at t_{n+1}
  double a, da;     // c beta
  double D, dD;     // x = W / D
  Vector6 W, dW;    // W = W0 - c h + a V
  double normW;     // |W|
  double r, dr;     // Gamma D - sqrt(2/3) |W|
};

struct StepConstants {
  const GvboLaw* law;
  double E, G, Etb, k2b, dt, A_n;
  Vector6 W0, h, V;
};

/// @return x^-n; by multiplication when n is a whole number up to 8 (Table 1's
/// k4 = 4: pow was a tenth of a membrane step), else std::pow.
double negativePower(double x, double n) {
  if (n == std::floor(n) && n >= 1 && n <= 8) {
    double r = x;
    for (int i = 1; i < static_cast<int>(n); ++i)
      r *= x;
    return 1 / r;
  }
  return std::pow(x, -n);
}

Scalars evaluate(const StepConstants& sc, double Gamma) {
  const GvboParameters& p = sc.law->parameters();
  Scalars s;
  s.Gamma = Gamma;
  const double ex = std::exp(-p.a3 * Gamma);
  const double psi = p.a1 + (p.a2 - p.a1) * ex;
  s.c = psi / sc.E;
  s.dc = -p.a3 * (p.a2 - p.a1) * ex / sc.E;
  s.k = p.k1 * negativePower(1 + Gamma / sc.k2b, p.k4);
  s.phi = sc.dt / (sc.E * s.k);
  s.dphi = s.phi * p.k4 / (sc.k2b + Gamma); // -phi k'/k
  const double q = Gamma * s.phi, dq = s.phi + Gamma * s.dphi;
  const double den = 1 + p.Ac * q;
  s.A = (sc.A_n + p.Ac * p.Af * q) / den;
  const double dA = p.Ac * (p.Af - sc.A_n) * dq / (den * den);
  const double beta = q * sc.E / s.A;
  const double dbeta = sc.E * (dq * s.A - q * dA) / (s.A * s.A);
  s.a = s.c * beta;
  s.da = s.dc * beta + s.c * dbeta;
  const double G3 = 3 * sc.G, EmG = sc.E - G3;
  s.D = (1 + s.a) * (1 + G3 * s.phi) + s.c * EmG * s.phi + (s.a + 1 - s.c) * sc.Etb * s.phi;
  s.dD = s.da * (1 + G3 * s.phi) + (1 + s.a) * G3 * s.dphi + s.dc * EmG * s.phi +
         s.c * EmG * s.dphi + (s.da - s.dc) * sc.Etb * s.phi + (s.a + 1 - s.c) * sc.Etb * s.dphi;
  s.W = sc.W0 - s.c * sc.h + s.a * sc.V;
  s.dW = -s.dc * sc.h + s.da * sc.V;
  s.normW = std::sqrt(std::max(contract(s.W, s.W), 0.0));
  s.r = Gamma * s.D - kSqrt23 * s.normW;
  s.dr = s.D + Gamma * s.dD - (s.normW > 0 ? kSqrt23 * contract(s.W, s.dW) / s.normW : 0.0);
  return s;
}

/// @return true when the Gamma of @p s solves r = 0 to round-off: its Newton
/// correction |r / dr| is at most 1e-14 of k2' + Gamma
bool gammaConverged(const StepConstants& sc, const Scalars& s) {
  return s.dr > 0 && std::abs(s.r) <= 1e-14 * (sc.k2b + s.Gamma) * s.dr;
}

/// @return where the overstress iteration starts without the last step's
/// Gamma: the elastic overstress sqrt(2/3) |W(0)| / D(0) (0 without one)
double elasticOverstress(const StepConstants& sc) {
  const Scalars s0 = evaluate(sc, 0.0);
  return s0.normW > 0 ? std::max(kSqrt23 * s0.normW / s0.D, 1e-300) : 0.0;
}

/// @return true when @p Gamma (the last step's) can start the iteration
bool usableGuess(double Gamma) {
  return Gamma > 0 && std::isfinite(Gamma);
}

/// Root of r(Gamma) = 0 on [0, inf): r(0) <= 0 and r grows without bound.
/// Newton from @p guess (the last step's Gamma: at a steady rate it is near
/// the root), safeguarded: the iterates keep a bracket [lo, hi] (hi infinite
/// until a positive residual is seen), and a Newton step that leaves it is
/// replaced by bisection, or by doubling while no upper end is known.
/// @return the root and the scalars evaluated at it (the last iterate, whose
/// Newton correction is below round-off of Gamma on the scale of k2 + Gamma,
/// or at which the bracket closed to that size)
Scalars solveGamma(const StepConstants& sc, double guess, int& iterations) {
  const GvboParameters& p = sc.law->parameters();
  const double psi0 = p.a1 + (p.a2 - p.a1);            // psi(0), as evaluate() forms it
  const Vector6 W_at_0 = sc.W0 - (psi0 / sc.E) * sc.h; // W(0): q = 0, so a = 0
  if (contract(W_at_0, W_at_0) == 0) {
    iterations = 0;
    return evaluate(sc, 0.0);
  }
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  double g = usableGuess(guess) ? guess : elasticOverstress(sc);
  for (iterations = 0; iterations < 400; ++iterations) {
    const Scalars s = evaluate(sc, g);
    if (s.r > 0)
      hi = g;
    else
      lo = g;
    // converged: the Newton correction is below round-off of Gamma on the
    // scale of k2 and Gamma (checked before the bracket, which a root met
    // exactly would leave), or the bracket closed on the root
    if (gammaConverged(sc, s) || hi - lo <= 1e-14 * (sc.k2b + g))
      return s;
    double next = s.dr > 0 ? g - s.r / s.dr : lo + 0.5 * (hi - lo);
    if (!(next > lo && next < hi))
      next = std::isfinite(hi) ? lo + 0.5 * (hi - lo) : 2 * std::max(g, lo);
    g = next;
  }
  throw Error("GVBO: the overstress iteration did not converge");
}

/// Everything of one step that does not depend on Gamma: the moduli at
/// J_{n+1}, the step's constants, the increment's trace and the state at t_n.
struct Step {
  GvboModuli m;
  double K = 0;   // bulk modulus at J_{n+1}
  double dth = 0; // volumetric strain increment
  double p_n = 0; // mean stress at t_n
  Vector6 s_n, f_n;
  StepConstants sc;
};

/// @param de the strain increment, tensor components (shear halved)
Step prepare(const GvboLaw& law, double J, double dt, const Vector6& de, const double* state_n) {
  const GvboParameters& p = law.parameters();
  Step st;
  st.m = gvboModuli(p, J);
  st.K = st.m.lambda + 2 * st.m.G / 3;
  st.sc.law = &law;
  st.sc.E = st.m.E;
  st.sc.G = st.m.G;
  st.sc.dt = dt;
  st.sc.A_n = state_n[GvboState::kA];
  st.sc.Etb = 2.0 / 3.0 * p.Et / (1 - p.Et / st.m.E);
  st.sc.k2b = p.k2 + p.k3 * (st.m.E - p.E0) / (p.Em - p.E0);
  st.dth = de[0] + de[1] + de[2];
  const Vector6 sig_n = Eigen::Map<const Vector6>(state_n + GvboState::kSigma);
  const Vector6 g_n = Eigen::Map<const Vector6>(state_n + GvboState::kG);
  st.f_n = Eigen::Map<const Vector6>(state_n + GvboState::kF);
  st.p_n = (sig_n[0] + sig_n[1] + sig_n[2]) / 3;
  st.s_n = deviator(sig_n);
  st.sc.h = 2 * st.m.G * deviator(de);
  st.sc.W0 = st.s_n - g_n + st.sc.h;
  st.sc.V = st.s_n - st.f_n + st.sc.h;
  return st;
}

/// The stress at t_{n+1} of the step @p st at the scalars @p s.
struct StressAt {
  Vector6 x;     // the overstress W / D
  Vector6 dev;   // the deviator s = s_n + h - 3 G phi x (eq. 3)
  Vector6 sigma; // s + p 1, p = p_n + K dth
  StressAt(const Step& st, const Scalars& s)
      : x(s.W / s.D), dev(st.s_n + st.sc.h - 3 * st.m.G * s.phi * x), sigma(dev) {
    sigma.head<3>().array() += st.p_n + st.K * st.dth;
  }
};

/// Writes the state at t_{n+1} of the step @p st at the scalars @p s.
void store(const Step& st, const Scalars& s, const StressAt& at, double* state) {
  const Vector6 f = st.f_n + st.sc.Etb * s.phi * at.x;
  const Vector6 g = at.dev - at.x;
  Eigen::Map<Vector6>(state + GvboState::kSigma) = at.sigma;
  Eigen::Map<Vector6>(state + GvboState::kG) = g;
  Eigen::Map<Vector6>(state + GvboState::kF) = f;
  state[GvboState::kA] = s.A;
  state[GvboState::kGamma] = s.Gamma;
}

} // namespace

GvboLaw::GvboLaw(const GvboParameters& p) : p_(p) {
  LAMINA_CHECK(p.E0 > 0 && std::isfinite(p.E0), "GVBO: E0 must be positive");
  LAMINA_CHECK(p.nu0 > -1 && p.nu0 < 0.5, "GVBO: nu0 must lie in (-1, 0.5)");
  LAMINA_CHECK(p.Et >= 0 && p.Et < p.E0, "GVBO: Et must lie in [0, E0)");
  LAMINA_CHECK(p.k1 > 0, "GVBO: k1 must be positive (s)");
  LAMINA_CHECK(p.k2 > 0, "GVBO: k2 must be positive (Pa)");
  LAMINA_CHECK(p.k3 >= 0, "GVBO: k3 must not be negative (Pa)");
  LAMINA_CHECK(p.k4 >= 0, "GVBO: k4 must not be negative");
  LAMINA_CHECK(p.Em > p.E0, "GVBO: Em must exceed E0");
  LAMINA_CHECK(p.A0 > 0, "GVBO: A0 must be positive (Pa)");
  LAMINA_CHECK(p.Ac >= 0, "GVBO: Ac must not be negative (1/s)");
  LAMINA_CHECK(p.Af >= 0, "GVBO: Af must not be negative (Pa)");
  LAMINA_CHECK(p.a3 >= 0, "GVBO: a3 must not be negative (1/Pa)");
}

void GvboLaw::initState(double* state) const {
  std::fill(state, state + GvboState::kSize, 0.0);
  state[GvboState::kA] = p_.A0;
}

Vector6 GvboLaw::elasticStrain(const Vector6& sigma, double J) const {
  const GvboModuli m = gvboModuli(p_, J);
  const double K = m.lambda + 2 * m.G / 3, mean = (sigma[0] + sigma[1] + sigma[2]) / 3;
  Vector6 eps;
  for (int i = 0; i < 3; ++i) {
    eps[i] = (sigma[i] - mean) / (2 * m.G) + mean / (3 * K);
    eps[3 + i] = sigma[3 + i] / m.G;
  }
  return eps;
}

Stiffness GvboLaw::elasticStiffness(double J) const {
  const GvboModuli m = gvboModuli(p_, J);
  return Stiffness::fromLame(m.lambda, m.G);
}

double GvboLaw::viscosity(double Gamma, double J) const {
  const double E = gvboModuli(p_, J).E;
  const double k2b = p_.k2 + p_.k3 * (E - p_.E0) / (p_.Em - p_.E0);
  return p_.k1 * std::pow(1 + Gamma / k2b, -p_.k4);
}

double GvboLaw::shape(double Gamma) const {
  return p_.a1 + (p_.a2 - p_.a1) * std::exp(-p_.a3 * Gamma);
}

double GvboLaw::kinematicModulus(double J) const {
  const double E = gvboModuli(p_, J).E;
  return 2.0 / 3.0 * p_.Et / (1 - p_.Et / E);
}

void GvboLaw::update(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
                     Matrix6* tangent) const {
  updateWithInfo(step, state_n, state, sigma, tangent, nullptr);
}

void GvboLaw::updateWithInfo(const PointStep& step, const double* state_n, double* state,
                             Vector6& sigma, Matrix6* tangent, GvboStepInfo* info) const {
  LAMINA_CHECK(step.dt >= 0, "GVBO: negative time step");
  // strain increment as a tensor (engineering shear -> tensor shear)
  Vector6 de = step.eps - step.eps_n;
  de.tail<3>() *= 0.5;
  const Step st = prepare(*this, step.J, step.dt, de, state_n);
  const GvboModuli& m = st.m;
  const double K = st.K;
  int iterations = 0;
  const Scalars s = solveGamma(st.sc, state_n[GvboState::kGamma], iterations);
  const StressAt at(st, s);
  sigma = at.sigma;
  store(st, s, at, state);
  const Vector6& x = at.x;
  if (info)
    *info = {s.Gamma, s.k, s.c * m.E, m.E, iterations};
  if (!tangent)
    return;
  // d sigma / d eps (engineering): K 1x1 + (2G - 3G phi alpha) M + b n^T,
  // M the deviatoric projector from engineering strain to tensor stress.
  const double alpha = 2 * m.G * (1 - s.c + s.a) / s.D;
  Matrix6& T = *tangent;
  T.setZero();
  const double a2 = 2 * m.G - 3 * m.G * s.phi * alpha;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      T(i, j) = K + a2 * ((i == j ? 1.0 : 0.0) - 1.0 / 3.0);
  for (int i = 3; i < 6; ++i)
    T(i, i) = 0.5 * a2;
  if (s.normW > 0 && s.dr > 0) {
    const Vector6 n = s.W / s.normW;
    const double dGamma = kSqrt23 * alpha * s.D / s.dr; // dGamma/d eps_j = dGamma * n_j
    const Vector6 y = (s.dW - x * s.dD) / s.D;          // d x / d Gamma at fixed strain
    const Vector6 b = -3 * m.G * (s.dphi * x + s.phi * y) * dGamma;
    T += b * n.transpose();
  }
}

bool GvboLaw::planeStressStep(const PlaneStressStep& ps, const double* state_n, double* state,
                              double tolerance, PlaneStressResult& out) const {
  // Isotropy keeps the transverse shears of state and strain zero when they
  // start so (nothing couples them to the in-plane and normal components):
  // then sigma_yz = sigma_xz = 0 hold exactly and one normal strain is left.
  if (ps.n_free != 0 || !(ps.dt >= 0) || ps.eps_n[4] != 0 || ps.eps_n[5] != 0)
    return false;
  for (const int at : {GvboState::kSigma, GvboState::kG, GvboState::kF})
    if (state_n[at + 4] != 0 || state_n[at + 5] != 0)
      return false;
  const GvboModuli m_n = gvboModuli(p_, ps.J2_n * ps.lambda3_n);
  // the elastic predictor of planeStressUpdate (isotropic: lambda (dxx + dyy
  // + z) + 2 G z = 0) and the same stress scale: max|C0| = lambda + 2 G
  double z = std::clamp(-m_n.lambda * (ps.deps_p[0] + ps.deps_p[1]) / (m_n.lambda + 2 * m_n.G),
                        -kMaxThicknessIncrement, kMaxThicknessIncrement);
  const double maxC0 = m_n.lambda + 2 * m_n.G;
  double Gamma = state_n[GvboState::kGamma];
  const bool guessed = usableGuess(Gamma);
  Vector6 de;
  de << ps.deps_p[0], ps.deps_p[1], 0, 0.5 * ps.deps_p[2], 0, 0;
  // Newton on (z, Gamma) for sigma_zz = 0 and the overstress equation r = 0,
  // the moduli at J(z) of each iterate; the Jacobian at fixed moduli (their
  // change with J within a step is of the order of the step's increment).
  for (int it = 0; it <= kPlaneStressMaxIterations; ++it) {
    de[2] = z;
    const Step st =
        prepare(*this, ps.J2 * midpointThicknessStretch(ps.lambda3_n, z), ps.dt, de, state_n);
    if (it == 0 && !guessed) // the law's own start (0 without overstress, as update())
      Gamma = elasticOverstress(st.sc);
    const Scalars s = evaluate(st.sc, Gamma);
    const StressAt at(st, s);
    if (!at.sigma.allFinite() || !std::isfinite(s.r) || !(s.dr > 0))
      return false;
    const Vector6 eps = strainAtEnd(ps, z);
    const double residual = std::abs(at.sigma[2]);
    // converged as planeStressUpdate's Newton and as the law's own update
    // (solveGamma) would be
    if (residual <= tolerance * planeStressScale(at.sigma, maxC0, ps.eps_n, eps) &&
        gammaConverged(st.sc, s)) {
      store(st, s, at, state);
      out = PlaneStressResult{};
      out.eps = eps;
      out.lambda3 = midpointThicknessStretch(ps.lambda3_n, z);
      out.sigma = at.sigma;
      out.iterations = it;
      out.residual = residual;
      return true;
    }
    // Jacobian: dW/dz = (1 - c + a) 2G dev(e_zz) and W deviatoric, so
    // W : dW/dz = (1 - c + a) 2G W_zz
    const double G = st.m.G, w = (1 - s.c + s.a) * 2 * G;
    const double xzz = at.x[2];
    const double a11 = st.K + 4.0 / 3.0 * G - 3 * G * s.phi * w * (2.0 / 3.0) / s.D;
    const double a12 = -3 * G * (s.dphi * xzz + s.phi * (s.dW[2] - xzz * s.dD) / s.D);
    const double a21 = s.normW > 0 ? -kSqrt23 * w * s.W[2] / s.normW : 0.0;
    const double a22 = s.dr;
    const double det = a11 * a22 - a12 * a21;
    if (!(std::abs(det) > 0) || !std::isfinite(det))
      return false;
    double dz = (a22 * at.sigma[2] - a12 * s.r) / det;
    double dGamma = (a11 * s.r - a21 * at.sigma[2]) / det;
    for (int halve = 0; std::abs(z - dz) > kMaxThicknessIncrement && halve < 60; ++halve) {
      dz *= 0.5; // a shorter step along the Newton direction
      dGamma *= 0.5;
    }
    z -= dz;
    Gamma -= dGamma;
    if (!(Gamma >= 0) || !std::isfinite(z)) // leave it to the safeguarded iterations
      return false;
  }
  return false;
}

} // namespace lamina::materials
