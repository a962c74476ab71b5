#include "materials/gvbo_lanes.hpp"

#include "core/vector_math.hpp"
#include "materials/gvbo_law.hpp"
#include "materials/plane_stress.hpp"

#include <algorithm>
#include <cmath>

// Every formula below is GvboLaw::planeStressStep's (gvbo_law.cpp), written
// per lane; the comments name the function of gvbo_law.cpp or gvbo.cpp that
// each block mirrors. A divisor used more than once is inverted once (a
// vector division costs about ten multiplications), so the lanes agree
// with the one-point step to round-off, not to the bit.

namespace lamina::materials {

namespace {

constexpr int W = kGvboLanes;
const double kSqrt23 = std::sqrt(2.0 / 3.0);

using Mask = core::LaneMask;
using core::finiteLane;

/// ln x and x^p = exp(p ln x) of every lane. A kernel of its own: inlined
/// at two places of the step, GCC unrolled one copy into scalar calls.
LAMINA_VECTOR_CLONES __attribute__((noinline)) void logAndPower(const double* x, double p,
                                                                double* lnx, double* xp) {
  LAMINA_LANES
  for (int l = 0; l < W; ++l) {
    lnx[l] = std::log(x[l]);
    xp[l] = std::exp(p * lnx[l]);
  }
}

/// The moduli at J (gvboModuli) on every lane; @p ok cleared where J is not
/// a positive finite number (that lane then computes at J = 1).
struct Moduli {
  double lambda[W], G[W], E[W];
  LAMINA_CLONE_INLINE void at(const GvboParameters& g, const double* J, Mask* ok) {
    const double lambda0 = g.E0 * g.nu0 / ((1 + g.nu0) * (1 - 2 * g.nu0));
    const double G0 = g.E0 / (2 * (1 + g.nu0));
    double Jg[W], lnJ[W], Jp[W];
    for (int l = 0; l < W; ++l) {
      const Mask good = (J[l] > 0) & finiteLane(J[l]);
      ok[l] = ok[l] & good;
      Jg[l] = good ? J[l] : 1.0;
    }
    logAndPower(Jg, g.p, lnJ, Jp); // J^p, one logarithm for both terms
    for (int l = 0; l < W; ++l) {
      lambda[l] = std::max(lambda0, Jp[l] * lambda0);
      G[l] = std::max(G0, Jp[l] * (G0 - lambda0 * lnJ[l]));
      const double e = G[l] * (3 * lambda[l] + 2 * G[l]) / (lambda[l] + G[l]);
      E[l] = std::max(e, g.E0);
    }
  }
};

/// The state at t_n that a step reads, per lane (prepare()).
struct StateN {
  double s[4][W]; // deviator of sigma_n: xx, yy, zz, xy
  double g[4][W], f[4][W];
  double p[W], A[W], Gamma[W];
};

/// A deviatoric 4-vector per lane (xx, yy, zz, xy).
using Lanes4 = double[4][W];

/// Everything of an iterate that does not depend on Gamma (prepare()).
struct StepLanes {
  Moduli m;
  double K[W], Etb[W], k2b[W], dth[W];
  double invE[W], invk2b[W]; // 1 / E, 1 / k2b
  Lanes4 h, W0, V;
};

/// The scalars of evaluate() at Gamma, per lane.
struct ScalarLanes {
  double c[W], dc[W], phi[W], dphi[W], A[W], a[W], da[W], D[W], dD[W], normW[W], r[W], dr[W];
  double invD[W], invNormW[W]; // 1 / D, 1 / |W| (0 where |W| = 0)
  Lanes4 Wv, dW;
};

/// x^n of every lane: by multiplication for whole n up to 8 (as
/// negativePower() of gvbo_law.cpp, whose x^-n is 1 over it), else std::pow.
LAMINA_CLONE_INLINE void powers(const double* x, double n, double* out) {
  if (n == std::floor(n) && n >= 1 && n <= 8) {
    const int k = static_cast<int>(n);
    for (int l = 0; l < W; ++l)
      out[l] = x[l];
    for (int i = 1; i < k; ++i)
      for (int l = 0; l < W; ++l)
        out[l] *= x[l];
    return;
  }
  for (int l = 0; l < W; ++l)
    out[l] = std::pow(x[l], n);
}

/// prepare() at J with the tensor increment (de0, de1, z, de3), per lane.
LAMINA_CLONE_INLINE void prepare(const GvboParameters& p, const double* J, const double* de0,
                                 const double* de1, const double* z, const double* de3,
                                 const StateN& sn, StepLanes& st, Mask* ok) {
  st.m.at(p, J, ok);
  const double k3 = p.k3 / (p.Em - p.E0);
  for (int l = 0; l < W; ++l) {
    const double E = st.m.E[l], G = st.m.G[l];
    st.invE[l] = 1 / E;
    st.K[l] = st.m.lambda[l] + (2.0 / 3.0) * G;
    st.Etb[l] = 2.0 / 3.0 * p.Et / (1 - p.Et * st.invE[l]);
    st.k2b[l] = p.k2 + k3 * (E - p.E0);
    st.invk2b[l] = 1 / st.k2b[l];
    st.dth[l] = de0[l] + de1[l] + z[l];
    const double mean = st.dth[l] * (1.0 / 3.0);
    const double twoG = 2 * G;
    st.h[0][l] = twoG * (de0[l] - mean);
    st.h[1][l] = twoG * (de1[l] - mean);
    st.h[2][l] = twoG * (z[l] - mean);
    st.h[3][l] = twoG * de3[l];
  }
  for (int i = 0; i < 4; ++i)
    for (int l = 0; l < W; ++l) {
      st.W0[i][l] = sn.s[i][l] - sn.g[i][l] + st.h[i][l];
      st.V[i][l] = sn.s[i][l] - sn.f[i][l] + st.h[i][l];
    }
}

/// a : b of two deviatoric 4-vectors (contract() with zero transverse shears).
LAMINA_CLONE_INLINE double contract4(const Lanes4& a, const Lanes4& b, int l) {
  return a[0][l] * b[0][l] + a[1][l] * b[1][l] + a[2][l] * b[2][l] + 2 * (a[3][l] * b[3][l]);
}

/// evaluate() at @p Gamma, per lane.
LAMINA_CLONE_INLINE void evaluate(const GvboParameters& p, double dt, const StepLanes& st,
                                  const StateN& sn, const double* Gamma, ScalarLanes& s) {
  double ex[W], base[W], kn[W];
  LAMINA_LANES
  for (int l = 0; l < W; ++l)
    ex[l] = std::exp(-p.a3 * Gamma[l]);
  for (int l = 0; l < W; ++l)
    base[l] = 1 + Gamma[l] * st.invk2b[l];
  powers(base, p.k4, kn); // k = k1 kn^-1
  const double dtk1 = dt / p.k1, da21 = -p.a3 * (p.a2 - p.a1);
  for (int l = 0; l < W; ++l) {
    const double E = st.m.E[l], G = st.m.G[l], g = Gamma[l], invE = st.invE[l];
    const double psi = p.a1 + (p.a2 - p.a1) * ex[l];
    s.c[l] = psi * invE;
    s.dc[l] = da21 * ex[l] * invE;
    s.phi[l] = dtk1 * kn[l] * invE; // dt / (E k)
    s.dphi[l] = s.phi[l] * p.k4 / (st.k2b[l] + g);
    const double q = g * s.phi[l], dq = s.phi[l] + g * s.dphi[l];
    const double invden = 1 / (1 + p.Ac * q);
    s.A[l] = (sn.A[l] + p.Ac * p.Af * q) * invden;
    const double dA = p.Ac * (p.Af - sn.A[l]) * dq * invden * invden;
    const double invA = 1 / s.A[l];
    const double beta = q * E * invA;
    const double dbeta = E * (dq * s.A[l] - q * dA) * invA * invA;
    s.a[l] = s.c[l] * beta;
    const double da = s.dc[l] * beta + s.c[l] * dbeta;
    const double G3 = 3 * G, EmG = E - G3, phi = s.phi[l], dphi = s.dphi[l];
    const double a = s.a[l], c = s.c[l], dc = s.dc[l], Etb = st.Etb[l];
    s.D[l] = (1 + a) * (1 + G3 * phi) + c * EmG * phi + (a + 1 - c) * Etb * phi;
    s.dD[l] = da * (1 + G3 * phi) + (1 + a) * G3 * dphi + dc * EmG * phi + c * EmG * dphi +
              (da - dc) * Etb * phi + (a + 1 - c) * Etb * dphi;
    s.invD[l] = 1 / s.D[l];
    s.da[l] = da;
  }
  for (int i = 0; i < 4; ++i)
    for (int l = 0; l < W; ++l) {
      s.Wv[i][l] = st.W0[i][l] - s.c[l] * st.h[i][l] + s.a[l] * st.V[i][l];
      s.dW[i][l] = -s.dc[l] * st.h[i][l] + s.da[l] * st.V[i][l];
    }
  for (int l = 0; l < W; ++l) {
    const double g = Gamma[l];
    s.normW[l] = std::sqrt(std::max(contract4(s.Wv, s.Wv, l), 0.0));
    s.invNormW[l] = s.normW[l] > 0 ? 1 / s.normW[l] : 0.0;
    s.r[l] = g * s.D[l] - kSqrt23 * s.normW[l];
    s.dr[l] = s.D[l] + g * s.dD[l] - kSqrt23 * contract4(s.Wv, s.dW, l) * s.invNormW[l];
  }
}

/// The Newton of GvboLaw::planeStressStep, per lane: the unknowns, the
/// inputs that stay fixed over the iterations and the lanes' status.
struct Newton {
  StateN sn;
  double de0[W], de1[W], de3[W]; // the tensor increment but zz (shear halved)
  double z[W], Gamma[W];         // the unknowns: deps_zz and the overstress invariant
  double maxC0[W], epsMax_n[W];  // the convergence test's stress scale terms
  Mask ok[W];                    // no reason yet to hand the lane back
  Mask active[W];                // still iterating
  Mask guessed[W];               // Gamma starts from the last step's
  Mask unguessed = false;        // some lane starts from the elastic overstress
};

/// The state at t_n, the conditions of GvboLaw::planeStressStep, its elastic
/// predictor and stress scale at the moduli of J_n.
LAMINA_CLONE_INLINE void start(const GvboParameters& p, double dt, const GvboLanes& io,
                               Newton& nw) {
  StateN& sn = nw.sn;
  double J[W];
  for (int l = 0; l < W; ++l) {
    const double* st = io.state_n[l];
    // GvboLaw::planeStressStep's conditions: no transverse shear anywhere
    Mask ok = (dt >= 0) & (io.eps_n[4][l] == 0) & (io.eps_n[5][l] == 0);
    for (const int at : {GvboState::kSigma, GvboState::kG, GvboState::kF})
      ok = ok & (st[at + 4] == 0) & (st[at + 5] == 0);
    nw.ok[l] = ok;
    const double* sig = st + GvboState::kSigma;
    sn.p[l] = (sig[0] + sig[1] + sig[2]) / 3;
    const double m = (sig[0] + sig[1] + sig[2]) / 3;
    for (int i = 0; i < 3; ++i)
      sn.s[i][l] = sig[i] - m;
    sn.s[3][l] = sig[3];
    for (int i = 0; i < 4; ++i) {
      sn.g[i][l] = st[GvboState::kG + i];
      sn.f[i][l] = st[GvboState::kF + i];
    }
    sn.A[l] = st[GvboState::kA];
    nw.Gamma[l] = st[GvboState::kGamma];
    J[l] = io.J2_n[l] * io.lambda3_n[l];
    nw.de0[l] = io.deps_p[0][l];
    nw.de1[l] = io.deps_p[1][l];
    nw.de3[l] = 0.5 * io.deps_p[2][l];
    double em = 0;
    for (int i = 0; i < 6; ++i)
      em = std::max(em, std::abs(io.eps_n[i][l]));
    nw.epsMax_n[l] = em;
  }
  Moduli mn;
  mn.at(p, J, nw.ok);
  for (int l = 0; l < W; ++l) {
    const double lam = mn.lambda[l], G = mn.G[l];
    nw.z[l] = std::clamp(-lam * (nw.de0[l] + nw.de1[l]) / (lam + 2 * G), -kMaxThicknessIncrement,
                         kMaxThicknessIncrement);
    nw.maxC0[l] = lam + 2 * G;
    nw.guessed[l] = (nw.Gamma[l] > 0) & finiteLane(nw.Gamma[l]);
    nw.unguessed = nw.unguessed | !nw.guessed[l];
    nw.active[l] = nw.ok[l];
  }
}

/// The stress of an iterate (StressAt) and the lanes it converges: sigma
/// finite, sigma_zz within the test and Gamma to round-off.
struct Iterate {
  double sig[4][W], dev[4][W], x[4][W];
  Mask done[W];
};

LAMINA_CLONE_INLINE void stressAt(const GvboLanes& io, const StepLanes& st, const ScalarLanes& s,
                                  double tolerance, Newton& nw, Iterate& at) {
  const StateN& sn = nw.sn;
  for (int i = 0; i < 4; ++i)
    for (int l = 0; l < W; ++l) {
      at.x[i][l] = s.Wv[i][l] * s.invD[l];
      at.dev[i][l] = sn.s[i][l] + st.h[i][l] - 3 * st.m.G[l] * s.phi[l] * at.x[i][l];
      at.sig[i][l] = at.dev[i][l];
    }
  for (int i = 0; i < 3; ++i)
    for (int l = 0; l < W; ++l)
      at.sig[i][l] += sn.p[l] + st.K[l] * st.dth[l];
  for (int l = 0; l < W; ++l) {
    const double s0 = at.sig[0][l], s1 = at.sig[1][l], s2 = at.sig[2][l], s3 = at.sig[3][l];
    const Mask fin = finiteLane(s.r[l]) & (s.dr[l] > 0) & finiteLane(s0) & finiteLane(s1) &
                     finiteLane(s2) & finiteLane(s3);
    const double smax =
        std::max(std::max(std::abs(s0), std::abs(s1)), std::max(std::abs(s2), std::abs(s3)));
    nw.ok[l] = nw.ok[l] & fin;
    nw.active[l] = nw.active[l] & nw.ok[l];
    // strainAtEnd's largest component: eps_n + (d0, d1, z, d2, 0, 0)
    const double e0 = io.eps_n[0][l] + io.deps_p[0][l], e1 = io.eps_n[1][l] + io.deps_p[1][l],
                 e2 = io.eps_n[2][l] + nw.z[l], e3 = io.eps_n[3][l] + io.deps_p[2][l];
    const double emax = std::max(
        std::max(std::max(std::abs(e0), std::abs(e1)), std::max(std::abs(e2), std::abs(e3))),
        std::max(std::abs(io.eps_n[4][l]), std::abs(io.eps_n[5][l])));
    const double scale = std::max(smax, nw.maxC0[l] * std::max(nw.epsMax_n[l], emax));
    at.done[l] = nw.active[l] & (std::abs(s2) <= tolerance * scale) & (s.dr[l] > 0) &
                 (std::abs(s.r[l]) <= 1e-14 * (st.k2b[l] + nw.Gamma[l]) * s.dr[l]);
  }
}

/// store() and the result of GvboLaw::planeStressStep for lane @p l.
LAMINA_CLONE_INLINE void storeLane(const StepLanes& st, const ScalarLanes& s, const Iterate& at,
                                   const Newton& nw, int l, GvboLanes& io) {
  double* out = io.state[l];
  const double Etbphi = st.Etb[l] * s.phi[l];
  for (int i = 4; i < 6; ++i)
    out[GvboState::kSigma + i] = out[GvboState::kG + i] = out[GvboState::kF + i] = 0;
  for (int i = 0; i < 4; ++i) {
    out[GvboState::kSigma + i] = at.sig[i][l];
    out[GvboState::kG + i] = at.dev[i][l] - at.x[i][l];
    out[GvboState::kF + i] = nw.sn.f[i][l] + Etbphi * at.x[i][l];
    io.sigma[i][l] = at.sig[i][l];
  }
  out[GvboState::kA] = s.A[l];
  out[GvboState::kGamma] = nw.Gamma[l];
  io.deps_zz[l] = nw.z[l];
  io.lambda3[l] = midpointThicknessStretch(io.lambda3_n[l], nw.z[l]);
  io.K[l] = st.K[l];
  io.G[l] = st.m.G[l];
}

/// The Newton step on (z, Gamma) of the active lanes, the Jacobian at fixed
/// moduli; a lane whose step fails the one-point step's checks is handed back.
LAMINA_CLONE_INLINE void newtonStep(const StepLanes& st, const ScalarLanes& s, const Iterate& at,
                                    Newton& nw) {
  double dz[W], dG[W];
  Mask good[W], far = false;
  for (int l = 0; l < W; ++l) {
    const double G = st.m.G[l], w = (1 - s.c[l] + s.a[l]) * 2 * G;
    const double xzz = at.x[2][l];
    const double a11 = st.K[l] + 4.0 / 3.0 * G - 3 * G * s.phi[l] * w * (2.0 / 3.0) * s.invD[l];
    const double a12 =
        -3 * G * (s.dphi[l] * xzz + s.phi[l] * (s.dW[2][l] - xzz * s.dD[l]) * s.invD[l]);
    const double a21 = -kSqrt23 * w * s.Wv[2][l] * s.invNormW[l];
    const double a22 = s.dr[l];
    const double det = a11 * a22 - a12 * a21, invdet = 1 / det;
    good[l] = nw.active[l] & (std::abs(det) > 0) & finiteLane(det);
    dz[l] = (a22 * at.sig[2][l] - a12 * s.r[l]) * invdet;
    dG[l] = (a11 * s.r[l] - a21 * at.sig[2][l]) * invdet;
    far = far | (good[l] & (std::abs(nw.z[l] - dz[l]) > kMaxThicknessIncrement));
  }
  if (far) // rare: a shorter step along the Newton direction
    for (int l = 0; l < W; ++l)
      for (int halve = 0;
           good[l] && std::abs(nw.z[l] - dz[l]) > kMaxThicknessIncrement && halve < 60; ++halve) {
        dz[l] *= 0.5;
        dG[l] *= 0.5;
      }
  for (int l = 0; l < W; ++l) {
    const double zn = nw.z[l] - dz[l], gn = nw.Gamma[l] - dG[l];
    const Mask active = nw.active[l];
    const Mask step = good[l] & (gn >= 0) & finiteLane(zn);
    nw.ok[l] = nw.ok[l] & ((1 - active) | step);
    nw.active[l] = step;
    nw.z[l] = step ? zn : nw.z[l];
    nw.Gamma[l] = step ? gn : nw.Gamma[l];
  }
}

} // namespace

LAMINA_VECTOR_CLONES
unsigned gvboPlaneStressLanes(const GvboParameters& p, double dt, double tolerance, GvboLanes& io) {
  Newton nw;
  start(p, dt, io, nw);
  for (int l = 0; l < W; ++l) { // defined outputs on the lanes not taken
    io.lambda3[l] = 1;
    for (int i = 0; i < 4; ++i)
      io.sigma[i][l] = 0;
  }
  unsigned taken = 0;
  StepLanes st;
  ScalarLanes s;
  Iterate at;
  for (int it = 0; it <= kPlaneStressMaxIterations; ++it) {
    Mask any = false;
    for (int l = 0; l < W; ++l)
      any = any | nw.active[l];
    if (!any)
      break;
    double J[W];
    for (int l = 0; l < W; ++l)
      J[l] = io.J2[l] * midpointThicknessStretch(io.lambda3_n[l], nw.z[l]);
    prepare(p, J, nw.de0, nw.de1, nw.z, nw.de3, nw.sn, st, nw.ok);
    if (it == 0 && nw.unguessed) { // the law's own start where there is no last Gamma
      const double zero[W] = {};
      evaluate(p, dt, st, nw.sn, zero, s);
      for (int l = 0; l < W; ++l)
        if (!nw.guessed[l])
          nw.Gamma[l] = s.normW[l] > 0 ? std::max(kSqrt23 * s.normW[l] * s.invD[l], 1e-300) : 0.0;
    }
    evaluate(p, dt, st, nw.sn, nw.Gamma, s);
    stressAt(io, st, s, tolerance, nw, at);
    for (int l = 0; l < W; ++l)
      if (at.done[l]) {
        storeLane(st, s, at, nw, l, io);
        taken |= 1u << l;
        nw.active[l] = false;
      }
    newtonStep(st, s, at, nw);
  }
  return taken;
}

} // namespace lamina::materials
