#include "homogenize/stencil.hpp"

// The rows the loops below read and write never overlap (distinct scratch
// rows, node rows and stress rows), which the compiler cannot prove from the
// pointers: without this it keeps them scalar (one double per instruction).
// No reduction is involved, so the results are the scalar loop's bit for bit.
#define LAMINA_STENCIL_SIMD _Pragma("omp simd")

namespace lamina::homogenize::stencil {

template <class T>
void gradientSums(const T* a, const T* b, const T* c, const T* d, int n2, T* X, T* Y, T* Z) {
  LAMINA_STENCIL_SIMD
  for (int k = 0; k < n2; ++k) {
    X[k] = (b[k] - a[k]) + (d[k] - c[k]);
    Y[k] = (c[k] + d[k]) - (a[k] + b[k]);
    Z[k] = (a[k] + b[k]) + (c[k] + d[k]);
  }
  X[n2] = X[0];
  Y[n2] = Y[0];
  Z[n2] = Z[0];
}

void strainRow(const double* sums, std::size_t L, const Grid& grid, const std::array<double, 6>& E,
               double* const eps[6]) {
  const RowSums<double> rs(sums, L, grid);
  LAMINA_STENCIL_SIMD
  for (int k = 0; k < grid.n[2]; ++k) {
    strainAt(rs, E, k, eps[0][k], eps[1][k], eps[2][k], eps[3][k], eps[4][k], eps[5][k]);
  }
}

void divergenceRow(const double* const prev_j[6], const double* const prev_m[6],
                   const double* const cur_j[6], const double* const cur_m[6], const Grid& grid,
                   double* scratch, double* const f[3]) {
  const int n2 = grid.n[2];
  const double cx = 0.25 / grid.h[0], cy = 0.25 / grid.h[1], cz = 0.25 / grid.h[2];
  const std::size_t L = static_cast<std::size_t>(n2) + 1; // index k+1 holds voxel k, 0 holds n2-1
  double* X0 = scratch; // x-terms of f_x, f_y, f_z: sigma_xx, xy, xz
  double* X3 = scratch + L;
  double* X5 = scratch + 2 * L;
  double* Y3 = scratch + 3 * L; // y-terms: sigma_xy, yy, yz
  double* Y1 = scratch + 4 * L;
  double* Y4 = scratch + 5 * L;
  double* Z5 = scratch + 6 * L; // z-terms: sigma_xz, yz, zz
  double* Z4 = scratch + 7 * L;
  double* Z2 = scratch + 8 * L;
  const double *p0j = prev_j[0], *p0m = prev_m[0], *c0j = cur_j[0], *c0m = cur_m[0];
  const double *p1j = prev_j[1], *p1m = prev_m[1], *c1j = cur_j[1], *c1m = cur_m[1];
  const double *p2j = prev_j[2], *p2m = prev_m[2], *c2j = cur_j[2], *c2m = cur_m[2];
  const double *p3j = prev_j[3], *p3m = prev_m[3], *c3j = cur_j[3], *c3m = cur_m[3];
  const double *p4j = prev_j[4], *p4m = prev_m[4], *c4j = cur_j[4], *c4m = cur_m[4];
  const double *p5j = prev_j[5], *p5m = prev_m[5], *c5j = cur_j[5], *c5m = cur_m[5];
  LAMINA_STENCIL_SIMD
  for (int k = 0; k < n2; ++k) {
    X0[k + 1] = (p0j[k] - c0j[k]) + (p0m[k] - c0m[k]);
    X3[k + 1] = (p3j[k] - c3j[k]) + (p3m[k] - c3m[k]);
    X5[k + 1] = (p5j[k] - c5j[k]) + (p5m[k] - c5m[k]);
    Y3[k + 1] = (p3m[k] + c3m[k]) - (p3j[k] + c3j[k]);
    Y1[k + 1] = (p1m[k] + c1m[k]) - (p1j[k] + c1j[k]);
    Y4[k + 1] = (p4m[k] + c4m[k]) - (p4j[k] + c4j[k]);
    Z5[k + 1] = (p5j[k] + c5j[k]) + (p5m[k] + c5m[k]);
    Z4[k + 1] = (p4j[k] + c4j[k]) + (p4m[k] + c4m[k]);
    Z2[k + 1] = (p2j[k] + c2j[k]) + (p2m[k] + c2m[k]);
  }
  for (double* a : {X0, X3, X5, Y3, Y1, Y4, Z5, Z4, Z2})
    a[0] = a[n2];
  double *fx = f[0], *fy = f[1], *fz = f[2];
  LAMINA_STENCIL_SIMD
  for (int k = 0; k < n2; ++k) {
    // voxel k sits at index k+1, voxel k-1 at index k
    fx[k] = cx * (X0[k + 1] + X0[k]) + cy * (Y3[k + 1] + Y3[k]) + cz * (Z5[k] - Z5[k + 1]);
    fy[k] = cx * (X3[k + 1] + X3[k]) + cy * (Y1[k + 1] + Y1[k]) + cz * (Z4[k] - Z4[k + 1]);
    fz[k] = cx * (X5[k + 1] + X5[k]) + cy * (Y4[k + 1] + Y4[k]) + cz * (Z2[k] - Z2[k + 1]);
  }
}

template <class T>
void xCombinations(const T* const prev[6], const T* const cur[6], int n2, T* out) {
  const std::size_t L = static_cast<std::size_t>(n2) + 1;
  T *D0 = out + 1, *D3 = out + L + 1, *D5 = out + 2 * L + 1;             // prev - cur
  T *S3 = out + 3 * L + 1, *S1 = out + 4 * L + 1, *S4 = out + 5 * L + 1; // prev + cur
  T *S5 = out + 6 * L + 1, *S2 = out + 7 * L + 1;
  const T *p0 = prev[0], *p1 = prev[1], *p2 = prev[2], *p3 = prev[3], *p4 = prev[4], *p5 = prev[5];
  const T *c0 = cur[0], *c1 = cur[1], *c2 = cur[2], *c3 = cur[3], *c4 = cur[4], *c5 = cur[5];
  LAMINA_STENCIL_SIMD
  for (int k = 0; k < n2; ++k) {
    D0[k] = p0[k] - c0[k];
    D3[k] = p3[k] - c3[k];
    D5[k] = p5[k] - c5[k];
    S3[k] = p3[k] + c3[k];
    S1[k] = p1[k] + c1[k];
    S4[k] = p4[k] + c4[k];
    S5[k] = p5[k] + c5[k];
    S2[k] = p2[k] + c2[k];
  }
  for (int s = 0; s < kXCombinations; ++s)
    out[static_cast<std::size_t>(s) * L] = out[static_cast<std::size_t>(s) * L + n2];
}

template <class T>
void divergenceFromCombinations(const T* cj, const T* cm, const Grid& grid, T* const f[3]) {
  const int n2 = grid.n[2];
  const T cx = static_cast<T>(0.25 / grid.h[0]), cy = static_cast<T>(0.25 / grid.h[1]),
          cz = static_cast<T>(0.25 / grid.h[2]);
  const std::size_t L = static_cast<std::size_t>(n2) + 1;
  const T *D0j = cj, *D3j = cj + L, *D5j = cj + 2 * L, *S3j = cj + 3 * L, *S1j = cj + 4 * L,
          *S4j = cj + 5 * L, *S5j = cj + 6 * L, *S2j = cj + 7 * L;
  const T *D0m = cm, *D3m = cm + L, *D5m = cm + 2 * L, *S3m = cm + 3 * L, *S1m = cm + 4 * L,
          *S4m = cm + 5 * L, *S5m = cm + 6 * L, *S2m = cm + 7 * L;
  T *fx = f[0], *fy = f[1], *fz = f[2];
  // the sums of divergenceRow (X across y: rows j + m; Y: m - j; Z: j + m),
  // voxel k at index k+1, voxel k-1 at index k
  auto X = [](const T* a, const T* b, int i) { return a[i] + b[i]; };
  auto Y = [](const T* a, const T* b, int i) { return b[i] - a[i]; };
  LAMINA_STENCIL_SIMD
  for (int k = 0; k < n2; ++k) {
    fx[k] = cx * (X(D0j, D0m, k + 1) + X(D0j, D0m, k)) +
            cy * (Y(S3j, S3m, k + 1) + Y(S3j, S3m, k)) + cz * (X(S5j, S5m, k) - X(S5j, S5m, k + 1));
    fy[k] = cx * (X(D3j, D3m, k + 1) + X(D3j, D3m, k)) +
            cy * (Y(S1j, S1m, k + 1) + Y(S1j, S1m, k)) + cz * (X(S4j, S4m, k) - X(S4j, S4m, k + 1));
    fz[k] = cx * (X(D5j, D5m, k + 1) + X(D5j, D5m, k)) +
            cy * (Y(S4j, S4m, k + 1) + Y(S4j, S4m, k)) + cz * (X(S2j, S2m, k) - X(S2j, S2m, k + 1));
  }
}

// double: the nonlinear field operator and the linear operator in double
// precision; float: the linear operator at loose tolerances
#define LAMINA_STENCIL_INSTANTIATE(T)                                                              \
  template void gradientSums<T>(const T*, const T*, const T*, const T*, int, T*, T*, T*);          \
  template void xCombinations<T>(const T* const[6], const T* const[6], int, T*);                   \
  template void divergenceFromCombinations<T>(const T*, const T*, const Grid&, T* const[3]);
LAMINA_STENCIL_INSTANTIATE(double)
LAMINA_STENCIL_INSTANTIATE(float)
#undef LAMINA_STENCIL_INSTANTIATE

} // namespace lamina::homogenize::stencil
