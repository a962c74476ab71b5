#include "membrane/model/law_lanes.hpp"

#include "core/vector_clones.hpp"
#include "materials/gvbo_lanes.hpp"
#include "materials/plane_stress.hpp"
#include "membrane/model/fabric_element.hpp"
#include "membrane/model/law_point.hpp"

#include <algorithm>
#include <cmath>

// Each block below is the per-lane form of a function of law_point.cpp or
// materials/kinematics.cpp, named in its comment.

namespace lamina::membrane {

namespace {

constexpr int W = kLawLanes;
static_assert(kLawLanes == materials::kGvboLanes, "one lane count for the element and the law");

/// 3 x 3 matrices per lane, column-major: m[r + 3 c][lane].
using Mat3 = double[9][W];
using core::finiteLane;
using Mask = core::LaneMask;

/// The columns of X^-T = cof(X) / det X into @p out, det X into @p det
/// (inverseTranspose of kinematics.cpp).
LAMINA_CLONE_INLINE void inverseTranspose(const Mat3& X, Mat3& out, double* det) {
  for (int c = 0; c < 3; ++c) { // column c of cof(X) = X_a x X_b
    const int a = 3 * ((c + 1) % 3), b = 3 * ((c + 2) % 3);
    for (int l = 0; l < W; ++l) {
      out[3 * c][l] = X[a + 1][l] * X[b + 2][l] - X[a + 2][l] * X[b + 1][l];
      out[3 * c + 1][l] = X[a + 2][l] * X[b][l] - X[a][l] * X[b + 2][l];
      out[3 * c + 2][l] = X[a][l] * X[b + 1][l] - X[a + 1][l] * X[b][l];
    }
  }
  for (int l = 0; l < W; ++l)
    det[l] = X[0][l] * out[0][l] + X[1][l] * out[1][l] + X[2][l] * out[2][l];
  for (int k = 0; k < 9; ++k)
    for (int l = 0; l < W; ++l)
      out[k][l] *= 1 / det[l];
}

/// @return whether any lane's flag is set
LAMINA_CLONE_INLINE bool anyLane(const Mask* m) {
  Mask any = 0;
  for (int l = 0; l < W; ++l)
    any |= m[l];
  return any != 0;
}

/// One scaled Newton iterate X <- (g X + X^-T / g) / 2 of the lanes @p active
/// (polarRotation of kinematics.cpp) from X^-T @p Xit and det X @p det;
/// @p done set where the correction fell below 1e-9 (squared 1e-18).
LAMINA_CLONE_INLINE void polarIterate(Mat3& X, const Mat3& Xit, const double* det, Mask* active,
                                      Mask* ok, Mask* done) {
  double d2[W] = {}, nXit[W] = {}, nX[W] = {}, g[W], step2[W] = {};
  for (int k = 0; k < 9; ++k)
    for (int l = 0; l < W; ++l) {
      const double d = Xit[k][l] - X[k][l];
      d2[l] += d * d;
      nXit[l] += Xit[k][l] * Xit[k][l];
      nX[l] += X[k][l] * X[k][l];
    }
  // scaling only far from R: near it, it would only add round-off
  double ig[W];
  for (int l = 0; l < W; ++l) {
    g[l] = d2[l] > 1e-4 ? std::sqrt(std::sqrt(nXit[l]) / std::sqrt(nX[l])) : 1.0;
    ig[l] = 1 / g[l];
  }
  Mask live[W];
  for (int l = 0; l < W; ++l) {
    live[l] = active[l] & (det[l] > 0);
    ok[l] = ok[l] & (live[l] | (1 - active[l])); // det <= 0 on the way: the SVD
  }
  for (int k = 0; k < 9; ++k)
    for (int l = 0; l < W; ++l) {
      const double next = 0.5 * (g[l] * X[k][l] + Xit[k][l] * ig[l]);
      const double d = next - X[k][l];
      step2[l] += d * d;
      X[k][l] = live[l] ? next : X[k][l];
    }
  for (int l = 0; l < W; ++l) {
    done[l] = live[l] & (step2[l] <= 1e-18);
    active[l] = live[l] & (1 - done[l]);
  }
}

/// The orthogonal polar factor of every lane's @p F, given @p FinvT = F^-T
/// and @p detF = det F (polarRotation of
/// kinematics.cpp: Newton's iteration with the Frobenius scaling far from
/// R, each lane stopping at its own converged iterate); @p ok cleared where
/// that iteration does not take the lane (det F <= 0 on the way, or no
/// convergence in 40 iterations: the one-element step takes the SVD).
LAMINA_CLONE_INLINE void polarRotations(const Mat3& F, const Mat3& FinvT, const double* detF,
                                        Mat3& R, Mask* ok) {
  Mat3 X, Xit, last;
  Mask active[W], done[W];
  double det[W];
  for (int k = 0; k < 9; ++k)
    for (int l = 0; l < W; ++l) {
      R[k][l] = k % 4 == 0 ? 1.0 : 0.0; // the lanes not taken keep the identity
      X[k][l] = F[k][l];
      Xit[k][l] = FinvT[k][l];
    }
  for (int l = 0; l < W; ++l) {
    det[l] = detF[l];
    active[l] = ok[l] & (det[l] > 0); // det F: the one-element step's first check
    ok[l] = active[l];
  }
  for (int it = 0; it < 40 && anyLane(active); ++it) {
    if (it > 0)
      inverseTranspose(X, Xit, det);
    polarIterate(X, Xit, det, active, ok, done);
    if (!anyLane(done))
      continue;
    inverseTranspose(X, last, det);
    for (int l = 0; l < W; ++l)
      ok[l] = ok[l] & (1 - (done[l] & (det[l] <= 0)));
    for (int k = 0; k < 9; ++k)
      for (int l = 0; l < W; ++l)
        R[k][l] = done[l] ? 0.5 * (X[k][l] + last[k][l]) : R[k][l];
  }
  for (int l = 0; l < W; ++l)
    ok[l] = ok[l] & (1 - active[l]); // still iterating after 40: not taken
}

/// [F | n], n the unit normal of the deformed element (completed() of
/// law_point.cpp), from F 3 x 2 column-major per lane; @p ok cleared for a
/// degenerate element.
LAMINA_CLONE_INLINE void completed(const double (&F)[6][W], Mat3& F3, Mask* ok) {
  double norm[W];
  for (int l = 0; l < W; ++l) {
    F3[6][l] = F[1][l] * F[5][l] - F[2][l] * F[4][l];
    F3[7][l] = F[2][l] * F[3][l] - F[0][l] * F[5][l];
    F3[8][l] = F[0][l] * F[4][l] - F[1][l] * F[3][l];
    norm[l] = std::sqrt(F3[6][l] * F3[6][l] + F3[7][l] * F3[7][l] + F3[8][l] * F3[8][l]);
    ok[l] = ok[l] & (norm[l] > 0) & finiteLane(norm[l]);
  }
  for (int k = 0; k < 6; ++k)
    for (int l = 0; l < W; ++l)
      F3[k][l] = F[k][l];
  for (int l = 0; l < W; ++l)
    norm[l] = 1 / norm[l];
  for (int k = 6; k < 9; ++k)
    for (int l = 0; l < W; ++l)
      F3[k][l] *= norm[l];
}

/// The in-plane components [xx, yy, xy] (engineering) of the rotation-free
/// increment of F_n -> F (rotationFreeIncrement of kinematics.cpp).
LAMINA_CLONE_INLINE void inPlaneIncrement(const Mat3& Fn, const Mat3& F, double (&deps)[3][W],
                                          Mask* ok) {
  Mat3 Fm, FmInvT, L, R;
  double det[W];
  for (int k = 0; k < 9; ++k)
    for (int l = 0; l < W; ++l)
      Fm[k][l] = 0.5 * (Fn[k][l] + F[k][l]);
  inverseTranspose(Fm, FmInvT, det);
  // Ldt = (F - F_n) Fm^-1, Fm^-1 = (Fm^-T)^T: L(r, c) = sum_k dF(r, k) FmInvT(c, k)
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < W; ++l)
        L[r + 3 * c][l] = (F[r][l] - Fn[r][l]) * FmInvT[c][l] +
                          (F[r + 3][l] - Fn[r + 3][l]) * FmInvT[c + 3][l] +
                          (F[r + 6][l] - Fn[r + 6][l]) * FmInvT[c + 6][l];
  polarRotations(Fm, FmInvT, det, R, ok); // clears ok where det Fm <= 0
  // deps = R^T D R, D = (L + L^T)/2, on the first two columns of R:
  // deps(i, j) = R_i . D R_j, the engineering shear deps(0, 1) + deps(1, 0)
  Mat3 D;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < W; ++l)
        D[r + 3 * c][l] = 0.5 * (L[r + 3 * c][l] + L[c + 3 * r][l]);
  double Q[2][3][W]; // D R_j
  for (int j = 0; j < 2; ++j)
    for (int r = 0; r < 3; ++r)
      for (int l = 0; l < W; ++l)
        Q[j][r][l] =
            D[r][l] * R[3 * j][l] + D[r + 3][l] * R[3 * j + 1][l] + D[r + 6][l] * R[3 * j + 2][l];
  auto dot = [&](int i, int j, int l) {
    return R[3 * i][l] * Q[j][0][l] + R[3 * i + 1][l] * Q[j][1][l] + R[3 * i + 2][l] * Q[j][2][l];
  };
  for (int l = 0; l < W; ++l) {
    deps[0][l] = dot(0, 0, l);
    deps[1][l] = dot(1, 1, l);
    deps[2][l] = dot(0, 1, l) + dot(1, 0, l);
  }
}

/// GvboLaw::elasticStrain of @p s at the moduli @p G, @p K, into @p e.
LAMINA_CLONE_INLINE void elasticStrain(double G, double K, const double (&s)[6], double (&e)[6]) {
  const double mean = (s[0] + s[1] + s[2]) / 3;
  for (int i = 0; i < 3; ++i) {
    e[i] = (s[i] - mean) / (2 * G) + mean / (3 * K);
    e[3 + i] = s[3 + i] / G;
  }
}

/// The completed gradients at t_n and t_{n+1} and the plane-stress step's
/// inputs (stepLawPoint's PlaneStressStep), per lane; @p ok cleared for a
/// lane the kinematics cannot take.
LAMINA_CLONE_INLINE void planeStressInputs(const LawLaneStep& io, materials::GvboLanes& g,
                                           Mask* ok) {
  using P = LawPoint;
  double Fn[6][W];
  for (int l = 0; l < W; ++l)
    for (int k = 0; k < 6; ++k)
      Fn[k][l] = io.block_n[l][P::kF + k];
  Mat3 Fn3, F3;
  completed(Fn, Fn3, ok);
  completed(io.F, F3, ok);
  double deps_geo[3][W];
  inPlaneIncrement(Fn3, F3, deps_geo, ok);
  for (int l = 0; l < W; ++l) {
    const double* bn = io.block_n[l];
    for (int i = 0; i < 6; ++i)
      g.eps_n[i][l] = bn[P::kEps + i];
    for (int i = 0; i < 3; ++i)
      g.deps_p[i][l] = deps_geo[i][l] + bn[P::kWrinkle + i]; // the previous wrinkles released
    g.lambda3_n[l] = bn[P::kLambda3];
    g.J2_n[l] = bn[P::kJ] / bn[P::kLambda3];
    g.state_n[l] = bn + P::kLaw;
    g.state[l] = io.block[l] + P::kLaw;
  }
  for (int l = 0; l < W; ++l) // det F3 = n . (F3_0 x F3_1) = |F3_0 x F3_1|
    g.J2[l] = F3[6][l] * (F3[1][l] * F3[5][l] - F3[2][l] * F3[4][l]) +
              F3[7][l] * (F3[2][l] * F3[3][l] - F3[0][l] * F3[5][l]) +
              F3[8][l] * (F3[0][l] * F3[4][l] - F3[1][l] * F3[3][l]);
}

/// The energy terms and the new history of lane @p l (the rest of
/// stepLawPoint, taut); @return false when its thickness stretch is not a
/// positive number (the one-element step's error).
LAMINA_CLONE_INLINE bool writeHistory(const LawLaneStep& io, const materials::GvboLanes& g,
                                      double dt, int l) {
  using P = LawPoint;
  const double* bn = io.block_n[l];
  const double lambda3 = g.lambda3[l];
  if (!(std::isfinite(lambda3) && lambda3 > 0))
    return false;
  const double J = g.J2[l] * lambda3, J_n = bn[P::kJ];
  const double sig[6] = {g.sigma[0][l], g.sigma[1][l], g.sigma[2][l], g.sigma[3][l], 0, 0};
  const double sig_n[6] = {bn[P::kSigma], bn[P::kSigma + 1], 0, bn[P::kSigma + 2], 0, 0};
  const double step[6] = {g.deps_p[0][l], g.deps_p[1][l], g.deps_zz[l], g.deps_p[2][l], 0, 0};
  double eps[6], deps[6];
  for (int i = 0; i < 6; ++i) {
    eps[i] = g.eps_n[i][l] + step[i]; // strainAtEnd
    deps[i] = eps[i] - g.eps_n[i][l];
  }
  const double G = g.G[l], K = g.K[l];
  double work = 0, psi = 0, e[6], ds[6];
  elasticStrain(G, K, sig, e);
  for (int i = 0; i < 6; ++i) {
    work += (J_n * sig_n[i] + J * sig[i]) * deps[i];
    psi += sig[i] * e[i];
    ds[i] = sig[i] - sig_n[i];
  }
  work *= 0.5;
  psi *= 0.5 * J;
  elasticStrain(G, K, ds, e);
  materials::Vector6 d; // the inelastic part of the increment
  for (int i = 0; i < 6; ++i)
    d[i] = deps[i] - e[i];
  double F[6];
  for (int k = 0; k < 6; ++k)
    F[k] = io.F[k][l];
  const double no_wrinkles[3] = {}; // taut
  LawPointEnd end;
  end.F = F;
  end.eps = eps;
  end.lambda3 = lambda3;
  end.eps_w = no_wrinkles;
  end.sigma[0] = sig[0];
  end.sigma[1] = sig[1];
  end.sigma[2] = sig[3];
  end.J = J;
  end.psi = psi;
  end.dissipated = work - (psi - bn[P::kPsi]);
  end.inelastic = equivalentDeviatoric(d);
  storeLawPoint(end, dt, bn, io.block[l]);
  return true;
}

/// S = J U2^-1 sigma U2^-1 (lawPointPk2), U2 = (C + s I) / sqrt(tr C + 2 s), per lane.
LAMINA_CLONE_INLINE void pk2(const materials::GvboLanes& g, LawLaneStep& io) {
  const auto& F = io.F;
  for (int l = 0; l < W; ++l) {
    const double c00 = F[0][l] * F[0][l] + F[1][l] * F[1][l] + F[2][l] * F[2][l];
    const double c11 = F[3][l] * F[3][l] + F[4][l] * F[4][l] + F[5][l] * F[5][l];
    const double c01 = F[0][l] * F[3][l] + F[1][l] * F[4][l] + F[2][l] * F[5][l];
    const double s = std::sqrt(c00 * c11 - c01 * c01);
    const double k = 1 / std::sqrt(c00 + c11 + 2 * s);
    const double u00 = (c00 + s) * k, u11 = (c11 + s) * k, u01 = c01 * k;
    const double idet = 1 / (u00 * u11 - u01 * u01);
    const double i00 = u11 * idet, i11 = u00 * idet, i01 = -u01 * idet;
    const double sxx = g.sigma[0][l], syy = g.sigma[1][l], sxy = g.sigma[3][l];
    // A = Uinv s, S = J A Uinv
    const double a00 = i00 * sxx + i01 * sxy, a01 = i00 * sxy + i01 * syy;
    const double a10 = i01 * sxx + i11 * sxy, a11 = i01 * sxy + i11 * syy;
    const double J = g.J2[l] * g.lambda3[l];
    io.S[0][l] = J * (a00 * i00 + a01 * i01);
    io.S[1][l] = J * (a10 * i01 + a11 * i11);
    io.S[2][l] = J * 0.5 * ((a00 * i01 + a01 * i11) + (a10 * i00 + a11 * i01));
  }
}

} // namespace

LAMINA_VECTOR_CLONES
unsigned stepGvboLawPoints(const materials::GvboLaw& law, bool tension_only, double dt,
                           LawLaneStep& io) {
  Mask ok[W];
  for (int l = 0; l < W; ++l)
    ok[l] = 1;
  materials::GvboLanes g;
  planeStressInputs(io, g, ok);
  unsigned taken =
      materials::gvboPlaneStressLanes(law.parameters(), dt, materials::kPlaneStressTolerance, g);
  for (int l = 0; l < W; ++l)
    if (!ok[l])
      taken &= ~(1u << l);
  if (tension_only) // wrinkled or slack: the one-element step's other solves
    for (int l = 0; l < W; ++l)
      if ((taken >> l & 1u) && principal2(g.sigma[0][l], g.sigma[1][l], g.sigma[3][l])[1] < 0)
        taken &= ~(1u << l);
  for (int l = 0; l < W; ++l)
    if ((taken >> l & 1u) && !writeHistory(io, g, dt, l))
      taken &= ~(1u << l);
  pk2(g, io);
  for (int l = 0; l < W; ++l) { // h A0 F S dN_a (fabric_element.hpp)
    double P[2][3];             // columns of h A0 F S
    for (int c = 0; c < 3; ++c) {
      P[0][c] = io.hA[l] * (io.F[c][l] * io.S[0][l] + io.F[3 + c][l] * io.S[2][l]);
      P[1][c] = io.hA[l] * (io.F[c][l] * io.S[2][l] + io.F[3 + c][l] * io.S[1][l]);
    }
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        io.f[3 * a + c][l] = P[0][c] * io.dN[2 * a][l] + P[1][c] * io.dN[2 * a + 1][l];
  }
  return taken;
}

} // namespace lamina::membrane
