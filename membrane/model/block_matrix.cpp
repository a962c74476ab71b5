#include "membrane/model/block_matrix.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace lamina::membrane {

namespace {
/// Rows per slice of the split storage (BlockMatrix::storeSlices): the lanes
/// of the split product.
constexpr int kSlice = 4;
} // namespace

BlockMatrix::BlockMatrix(const SparseMatrix& A, BlockStorage storage) {
  LAMINA_CHECK(A.rows() % 3 == 0 && A.rows() == A.cols(), "BlockMatrix needs a 3n x 3n matrix");
  const int n = static_cast<int>(A.rows() / 3);
  n_ = n;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* v = A.valuePtr();
  start_.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    const int len = outer[3 * i + 1] - outer[3 * i];
    LAMINA_CHECK(len % 3 == 0 && outer[3 * i + 2] - outer[3 * i + 1] == len &&
                     outer[3 * i + 3] - outer[3 * i + 2] == len,
                 "BlockMatrix: row ", 3 * i, " is not made of 3x3 blocks");
    start_[i + 1] = start_[i] + len / 3;
  }
  col_.resize(start_[n]);
  val_.resize(9 * static_cast<size_t>(start_[n]));
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < start_[i + 1] - start_[i]; ++k) {
      const int b = start_[i] + k;
      col_[b] = inner[outer[3 * i] + 3 * k] / 3;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          val_[9 * b + 3 * c + d] = v[outer[3 * i + c] + 3 * k + d];
    }
  if (storage == BlockStorage::Automatic) {
    shareRepeatedRows();
    if (!kind_.empty())
      return;
  }
  storePlainBlocks(storage == BlockStorage::Automatic);
}

void BlockMatrix::storePlainBlocks(bool may_split) {
  const std::size_t nb = col_.size();
  // Row-major values: (0,2) at 2, (1,2) at 5, (2,0) at 6, (2,1) at 7.
  split_ = may_split && nb > 0;
  for (std::size_t b = 0; b < nb && split_; ++b) {
    const double* m = val_.data() + 9 * b;
    split_ = m[2] == 0 && m[5] == 0 && m[6] == 0 && m[7] == 0;
  }
  if (split_) {
    storeSlices();
    return;
  }
  // Column-major 3x3 blocks (plainRows() loads a column at once), one pad
  // value so the last column's 4-wide load stays inside.
  for (std::size_t b = 0; b < nb; ++b) {
    double* m = val_.data() + 9 * b;
    std::swap(m[1], m[3]);
    std::swap(m[2], m[6]);
    std::swap(m[5], m[7]);
  }
  val_.push_back(0.0);
}

void BlockMatrix::storeSlices() {
  // Slice q holds rows [kSlice q, kSlice q + kSlice); its slot k holds block k
  // of each of those rows (per lane its column, its four in-plane values in
  // val_ and A(2,2) in val22_), and a row shorter
  // than the slice's longest ends in zero blocks on its own column.
  const int n = n_;
  // The AVX2 kernel gathers at s j + c o < 3 n as 32-bit indices.
  LAMINA_CHECK(3LL * n <= std::numeric_limits<int>::max(), "BlockMatrix: ", n,
               " nodes are more than the split product indexes");
  const int slices = (n + kSlice - 1) / kSlice;
  std::vector<int> sstart(slices + 1, 0);
  for (int q = 0; q < slices; ++q) {
    int len = 0;
    for (int i = kSlice * q; i < std::min(n, kSlice * (q + 1)); ++i)
      len = std::max(len, start_[i + 1] - start_[i]);
    sstart[q + 1] = sstart[q] + len;
  }
  const auto slots = static_cast<std::size_t>(sstart[slices]);
  std::vector<int> col(kSlice * slots);
  std::vector<double> val(4 * kSlice * slots, 0.0), val22(kSlice * slots, 0.0);
  for (int q = 0; q < slices; ++q)
    for (int l = 0; l < kSlice; ++l) {
      const int i = std::min(n - 1, kSlice * q + l); // lanes past the last row: zeros
      const int len = kSlice * q + l < n ? start_[i + 1] - start_[i] : 0;
      for (int k = 0; k < sstart[q + 1] - sstart[q]; ++k) {
        const auto slot = static_cast<std::size_t>(sstart[q] + k);
        col[kSlice * slot + l] = k < len ? col_[start_[i] + k] : i;
        if (k >= len)
          continue;
        const double* m = val_.data() + 9 * static_cast<std::size_t>(start_[i] + k); // row-major
        double* w = val.data() + 4 * kSlice * slot + l;
        w[0] = m[0]; // a00, a10, a01, a11, each kSlice lanes apart
        w[kSlice] = m[3];
        w[2 * kSlice] = m[1];
        w[3 * kSlice] = m[4];
        val22[kSlice * slot + l] = m[8];
      }
    }
  start_ = std::move(sstart);
  col_ = std::move(col);
  val_ = std::move(val);
  val22_ = std::move(val22);
}

void BlockMatrix::shareRepeatedRows() {
  const int n = n_;
  if (n < 64)
    return;
  const int limit = n / 16;
  std::unordered_map<std::string, int> seen;
  std::vector<int> kind(n), first;
  std::string key;
  auto sameRow = [&](int i, int r, double quantum) {
    if (start_[i + 1] - start_[i] != start_[r + 1] - start_[r])
      return false;
    for (int b = start_[i], c = start_[r]; b < start_[i + 1]; ++b, ++c) {
      if (col_[b] - i != col_[c] - r)
        return false;
      for (int q = 0; q < 9; ++q)
        if (std::abs(val_[9 * b + q] - val_[9 * c + q]) > quantum)
          return false;
    }
    return true;
  };
  for (int i = 0; i < n; ++i) {
    double scale = 0;
    for (int b = start_[i]; b < start_[i + 1]; ++b)
      for (int q = 0; q < 9; ++q)
        scale = std::max(scale, std::abs(val_[9 * b + q]));
    const double quantum = scale > 0 ? 1e-14 * scale : 1.0;
    // The previous node's row first: equal within the quantum, the two nodes
    // join one run even where round-off puts them on either side of a level.
    if (i > 0 && sameRow(i, first[kind[i - 1]], quantum)) {
      kind[i] = kind[i - 1];
      continue;
    }
    key.clear();
    for (int b = start_[i]; b < start_[i + 1]; ++b) {
      const std::int32_t off = col_[b] - i;
      key.append(reinterpret_cast<const char*>(&off), sizeof off);
      for (int q = 0; q < 9; ++q) {
        const auto level = static_cast<std::int64_t>(std::llround(val_[9 * b + q] / quantum));
        key.append(reinterpret_cast<const char*>(&level), sizeof level);
      }
    }
    const auto it = seen.emplace(key, static_cast<int>(first.size()));
    if (it.second) {
      first.push_back(i);
      if (static_cast<int>(first.size()) > limit)
        return; // not a repeated stencil: keep the plain block storage
    }
    kind[i] = it.first->second;
  }
  kstart_.assign(1, 0);
  for (int r : first) {
    for (int b = start_[r]; b < start_[r + 1]; ++b) {
      koff_.push_back(col_[b] - r);
      kval_.insert(kval_.end(), val_.begin() + 9 * b, val_.begin() + 9 * b + 9);
    }
    kstart_.push_back(static_cast<int>(koff_.size()));
  }
  kind_ = std::move(kind);
  run_begin_.clear();
  for (int i = 0; i < n; ++i)
    if (i == 0 || kind_[i] != kind_[i - 1])
      run_begin_.push_back(i);
  run_begin_.push_back(n);
  std::vector<int>().swap(col_);
  std::vector<double>().swap(val_);
  std::vector<int>().swap(start_);
}

namespace {

/// Planar y = A x on the nodes [i0, i1) of one run: every node applies the
/// blocks m[9 b..] at column offsets off[b], b in [0, nb). @return x.y there.
LAMINA_VECTOR_CLONES
double runProduct(const int* off, const double* m, int nb, int n, const double* __restrict x,
                  double* __restrict y, int i0, int i1) {
  const double* __restrict x0 = x;
  const double* __restrict x1 = x + n;
  const double* __restrict x2 = x + 2 * static_cast<std::ptrdiff_t>(n);
  double* __restrict y0 = y;
  double* __restrict y1 = y + n;
  double* __restrict y2 = y + 2 * static_cast<std::ptrdiff_t>(n);
  // The first block's terms are added to an explicit +0 (0 + t, the bits of
  // a zeroed y plus t) instead of a zeroing pass before.
  if (nb == 0)
    for (int i = i0; i < i1; ++i)
      y0[i] = y1[i] = y2[i] = 0;
  for (int b = 0; b < nb; ++b, m += 9) {
    const std::ptrdiff_t o = off[b];
    const double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3], m4 = m[4], m5 = m[5], m6 = m[6],
                 m7 = m[7], m8 = m[8];
    if (b == 0) {
      for (int i = i0; i < i1; ++i) {
        const double a = x0[i + o], c = x1[i + o], d = x2[i + o];
        y0[i] = 0.0 + (m0 * a + m1 * c + m2 * d);
        y1[i] = 0.0 + (m3 * a + m4 * c + m5 * d);
        y2[i] = 0.0 + (m6 * a + m7 * c + m8 * d);
      }
      continue;
    }
    for (int i = i0; i < i1; ++i) {
      const double a = x0[i + o], c = x1[i + o], d = x2[i + o];
      y0[i] += m0 * a + m1 * c + m2 * d;
      y1[i] += m3 * a + m4 * c + m5 * d;
      y2[i] += m6 * a + m7 * c + m8 * d;
    }
  }
  double dot = 0;
#pragma omp simd reduction(+ : dot)
  for (int i = i0; i < i1; ++i)
    dot += x0[i] * y0[i] + x1[i] * y1[i] + x2[i] * y2[i];
  return dot;
}

/// Stores row @p i's result (@p y0, @p y1, @p y2) in @p y (component c of
/// node i at s i + c o) and @return its part of x.y.
inline double storeRow(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i,
                       double y0, double y1, double y2) {
  double* yi = y + s * i;
  const double* xi = x + s * i;
  yi[0] = y0;
  yi[o] = y1;
  yi[2 * o] = y2;
  return xi[0] * y0 + xi[o] * y1 + xi[2 * o] * y2;
}

/// Plain blocks (column-major: m[3 d + c] = A(c, d)) on the rows [i0, i1):
/// component c of node j of x and y at s j + c o (interleaved: s = 3, o = 1;
/// planar: s = 1, o = n). Per row the operations and their order of the
/// row-major product y_c += A(c,0) x_0 + A(c,1) x_1 + A(c,2) x_2, block
/// after block. @return x.y on those rows, summed in node order.
double plainRowsScalar(const int* start, const int* col, const double* val, const double* x,
                       double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  for (int i = i0; i < i1; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 9 * static_cast<std::size_t>(b);
      const double* xj = x + s * col[b];
      const double a = xj[0], c = xj[o], d = xj[2 * o];
      y0 += m[0] * a + m[3] * c + m[6] * d;
      y1 += m[1] * a + m[4] * c + m[7] * d;
      y2 += m[2] * a + m[5] * c + m[8] * d;
    }
    dot += storeRow(x, y, s, o, i, y0, y1, y2);
  }
  return dot;
}

/// Split blocks in slices (BlockMatrix::storeSlices) on the rows [i0, i1):
/// per row the products and sums of plainRowsScalar() without the terms that
/// are exact zeros, and the slice's padding adds zeros, so the same numbers
/// as the 3x3 blocks (up to the sign of a zero; for a finite x: with an
/// infinite x_i the padding's 0 x_i makes row i NaN). The lanes of a slice are
/// its rows; rows of a slice outside [i0, i1) are computed, not stored.
/// @return x.y on [i0, i1), summed in node order.
double slicedRows(const int* sstart, const int* col, const double* val, const double* val22,
                  const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  for (int q = i0 / kSlice; kSlice * q < i1; ++q) {
    double y0[kSlice] = {}, y1[kSlice] = {}, y2[kSlice] = {};
    for (int k = sstart[q]; k < sstart[q + 1]; ++k) {
      const int* c = col + kSlice * static_cast<std::size_t>(k);
      const double* m = val + 4 * kSlice * static_cast<std::size_t>(k);
      const double* m22 = val22 + kSlice * static_cast<std::size_t>(k);
      for (int l = 0; l < kSlice; ++l) {
        const double* xj = x + s * c[l];
        const double a = xj[0], b = xj[o];
        y0[l] += m[l] * a + m[2 * kSlice + l] * b;
        y1[l] += m[kSlice + l] * a + m[3 * kSlice + l] * b;
        y2[l] += m22[l] * xj[2 * o];
      }
    }
    const int r0 = std::max(i0, kSlice * q), r1 = std::min(i1, kSlice * (q + 1));
    for (int i = r0; i < r1; ++i) {
      const int l = i - kSlice * q;
      dot += storeRow(x, y, s, o, i, y0[l], y1[l], y2[l]);
    }
  }
  return dot;
}

/// Stores the normal component @p y2 of row @p i in @p y (with @p StoreZeros
/// its +0 in-plane components too) and @return its part of x.y: the number
/// storeRow() gives when x_0, x_1 are zeros and y_0 = y_1 = +0
/// (x_0 y_0 + x_1 y_1 is a zero, which adds nothing to a non-zero x_2 y_2;
/// a sum that starts at +0 never becomes -0, so adding a zero of either
/// sign leaves it as it is). Written 0 + x_2 y_2, so that a compiler that
/// fuses multiply-adds fuses it as it fuses storeRow()'s sum (into the
/// term, not into the caller's running sum).
template <bool StoreZeros>
inline double storeNormal(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i,
                          double y2) {
  double* yi = y + s * i;
  if (StoreZeros)
    yi[0] = yi[o] = 0.0;
  yi[2 * o] = y2;
  return 0.0 + x[s * i + 2 * o] * y2;
}

/// The normal component of slicedRows() (A(2,2) x_2, the same operations in
/// the same order), for an x whose in-plane components are zero; with
/// @p StoreZeros the +0 in-plane components of y are stored too.
template <bool StoreZeros>
double slicedNormalRows(const int* sstart, const int* col, const double* val22, const double* x,
                        double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  const double* x2 = x + 2 * o;
  for (int q = i0 / kSlice; kSlice * q < i1; ++q) {
    double y2[kSlice] = {};
    for (int k = sstart[q]; k < sstart[q + 1]; ++k) {
      const int* c = col + kSlice * static_cast<std::size_t>(k);
      const double* m22 = val22 + kSlice * static_cast<std::size_t>(k);
      for (int l = 0; l < kSlice; ++l)
        y2[l] += m22[l] * x2[s * c[l]];
    }
    const int r0 = std::max(i0, kSlice * q), r1 = std::min(i1, kSlice * (q + 1));
    for (int i = r0; i < r1; ++i)
      dot += storeNormal<StoreZeros>(x, y, s, o, i, y2[i - kSlice * q]);
  }
  return dot;
}

#if defined(__GNUC__) && defined(__x86_64__)
#define LAMINA_AVX2_SLICES 1
static_assert(kSlice == 4, "the AVX2 kernel takes a slice in one 4-wide register");
/// @return p[j[l]], l = 0..3 (the masked form: GCC 12 warns that the plain
/// one reads an unset register)
__attribute__((target("avx2"), always_inline)) inline __m256d gather(const double* p, __m128i j) {
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), p, j,
                                  _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8);
}

/// slicedRows() with a slice's four rows in one AVX2 register (x gathered):
/// the same multiplications and additions in the same order per row (no
/// FMA: no contraction), so the same bits.
__attribute__((target("avx2"))) double slicedRowsAvx2(const int* sstart, const int* col,
                                                      const double* val, const double* val22,
                                                      const double* x, double* y, std::ptrdiff_t s,
                                                      std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  const __m128i stride = _mm_set1_epi32(static_cast<int>(s));

  for (int q = i0 / kSlice; kSlice * q < i1; ++q) {
    __m256d y0 = _mm256_setzero_pd(), y1 = y0, y2 = y0;
    for (int k = sstart[q]; k < sstart[q + 1]; ++k) {
      const double* m = val + 4 * kSlice * static_cast<std::size_t>(k);
      const __m128i j = _mm_mullo_epi32(
          _mm_loadu_si128(reinterpret_cast<const __m128i*>(col + kSlice * std::size_t(k))), stride);
      const __m256d a = gather(x, j), b = gather(x + o, j);
      y0 = _mm256_add_pd(y0, _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(m), a),
                                           _mm256_mul_pd(_mm256_loadu_pd(m + 8), b)));
      y1 = _mm256_add_pd(y1, _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(m + 4), a),
                                           _mm256_mul_pd(_mm256_loadu_pd(m + 12), b)));
      y2 = _mm256_add_pd(y2, _mm256_mul_pd(_mm256_loadu_pd(val22 + kSlice * std::size_t(k)),
                                           gather(x + 2 * o, j)));
    }
    alignas(32) double v0[kSlice], v1[kSlice], v2[kSlice];
    _mm256_store_pd(v0, y0);
    _mm256_store_pd(v1, y1);
    _mm256_store_pd(v2, y2);
    const int r0 = std::max(i0, kSlice * q), r1 = std::min(i1, kSlice * (q + 1));
    for (int i = r0; i < r1; ++i) {
      const int l = i - kSlice * q;
      dot += storeRow(x, y, s, o, i, v0[l], v1[l], v2[l]);
    }
  }
  return dot;
}

/// slicedNormalRows() with a slice's four rows in one AVX2 register: the
/// same bits.
template <bool StoreZeros>
__attribute__((target("avx2"))) double
slicedNormalRowsAvx2(const int* sstart, const int* col, const double* val22, const double* x,
                     double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  const __m128i stride = _mm_set1_epi32(static_cast<int>(s));
  const double* x2 = x + 2 * o;
  for (int q = i0 / kSlice; kSlice * q < i1; ++q) {
    __m256d y2 = _mm256_setzero_pd();
    for (int k = sstart[q]; k < sstart[q + 1]; ++k) {
      const __m128i j = _mm_mullo_epi32(
          _mm_loadu_si128(reinterpret_cast<const __m128i*>(col + kSlice * std::size_t(k))), stride);
      y2 = _mm256_add_pd(
          y2, _mm256_mul_pd(_mm256_loadu_pd(val22 + kSlice * std::size_t(k)), gather(x2, j)));
    }
    alignas(32) double v2[kSlice];
    _mm256_store_pd(v2, y2);
    const int r0 = std::max(i0, kSlice * q), r1 = std::min(i1, kSlice * (q + 1));
    for (int i = r0; i < r1; ++i)
      dot += storeNormal<StoreZeros>(x, y, s, o, i, v2[i - kSlice * q]);
  }
  return dot;
}
#endif

#if defined(__GNUC__) && defined(__x86_64__)
#define LAMINA_AVX_BLOCKS 1
/// plainRowsScalar() with the three rows of a block in one AVX register:
/// the same multiplications and additions in the same order per component
/// (AVX without FMA: no contraction), so the same bits.
__attribute__((target("avx"))) double plainRowsAvx(const int* start, const int* col,
                                                   const double* val, const double* x, double* y,
                                                   std::ptrdiff_t s, std::ptrdiff_t o, int i0,
                                                   int i1) {
  double dot = 0;
  for (int i = i0; i < i1; ++i) {
    __m256d acc = _mm256_setzero_pd();
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 9 * static_cast<std::size_t>(b);
      const double* xj = x + s * col[b];
      __m256d t = _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(m), _mm256_broadcast_sd(xj)),
                                _mm256_mul_pd(_mm256_loadu_pd(m + 3), _mm256_broadcast_sd(xj + o)));
      t = _mm256_add_pd(t, _mm256_mul_pd(_mm256_loadu_pd(m + 6), _mm256_broadcast_sd(xj + 2 * o)));
      acc = _mm256_add_pd(acc, t);
    }
    alignas(32) double v[4];
    _mm256_store_pd(v, acc);
    dot += storeRow(x, y, s, o, i, v[0], v[1], v[2]);
  }
  return dot;
}
#endif

/// The kernel BlockMatrix::useKernel chose.
BlockKernel g_kernel = BlockKernel::Fastest;
/// What BlockMatrix::usePlaneSkipping chose.
PlaneSkipping g_skipping = PlaneSkipping::Automatic;

/// Below this many node rows threads cost more than they save.
constexpr int kParallelNodes = 10000;

} // namespace

void toPlanar(const double* a, double* p, int n, int i0, int i1) {
  for (int i = i0; i < i1; ++i)
    for (int c = 0; c < 3; ++c)
      p[static_cast<std::ptrdiff_t>(c) * n + i] = a[3 * static_cast<std::ptrdiff_t>(i) + c];
}

void fromPlanar(const double* p, double* a, int n, int i0, int i1) {
  for (int i = i0; i < i1; ++i)
    for (int c = 0; c < 3; ++c)
      a[3 * static_cast<std::ptrdiff_t>(i) + c] = p[static_cast<std::ptrdiff_t>(c) * n + i];
}

bool inPlaneZero(const double* v, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  bool zero = true;
  for (int i = i0; i < i1 && zero; ++i)
    zero = v[s * i] == 0 && v[s * i + o] == 0;
  return zero;
}

void BlockMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  if (kind_.empty())
    product<false>(x, y);
  else
    productViaPlanar<false>(x, y);
}

double BlockMatrix::multiplyDot(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  return kind_.empty() ? product<true>(x, y) : productViaPlanar<true>(x, y);
}

double BlockMatrix::multiplyPlanar(const double* x, double* y, int begin, int end,
                                   BlockPlanes planes) const {
  const int n = n_;
  if (planes == BlockPlanes::Normal) {
    LAMINA_ASSERT(split_); // the normal plane alone needs split blocks
    return normalRows(x, y, 1, n, begin, end, false);
  }
  if (!kind_.empty()) {
    double dot = 0;
    forEachRun(begin, end, [&](int b, int e, int row) {
      dot += runProduct(koff_.data() + kstart_[row], kval_.data() + 9 * std::size_t(kstart_[row]),
                        kstart_[row + 1] - kstart_[row], n, x, y, b, e);
    });
    return dot;
  }
  // Plain blocks: one node at a time, columns gathered from the three planes.
  return plainRows(x, y, 1, n, begin, end);
}

void BlockMatrix::useKernel(BlockKernel kernel) {
  g_kernel = kernel;
}

void BlockMatrix::usePlaneSkipping(PlaneSkipping skipping) {
  g_skipping = skipping;
}

bool BlockMatrix::skipsZeroPlanes() {
  return g_skipping == PlaneSkipping::Automatic;
}

double BlockMatrix::plainRows(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o,
                              int begin, int end) const {
  if (split_) {
#ifdef LAMINA_AVX2_SLICES
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2 && g_kernel == BlockKernel::Fastest)
      return slicedRowsAvx2(start_.data(), col_.data(), val_.data(), val22_.data(), x, y, s, o,
                            begin, end);
#endif
    return slicedRows(start_.data(), col_.data(), val_.data(), val22_.data(), x, y, s, o, begin,
                      end);
  }
#ifdef LAMINA_AVX_BLOCKS
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx && g_kernel == BlockKernel::Fastest)
    return plainRowsAvx(start_.data(), col_.data(), val_.data(), x, y, s, o, begin, end);
#endif
  return plainRowsScalar(start_.data(), col_.data(), val_.data(), x, y, s, o, begin, end);
}

double BlockMatrix::normalRows(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o,
                               int begin, int end, bool store_zeros) const {
  const int *ss = start_.data(), *col = col_.data();
  const double* a22 = val22_.data();
#ifdef LAMINA_AVX2_SLICES
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && g_kernel == BlockKernel::Fastest)
    return store_zeros ? slicedNormalRowsAvx2<true>(ss, col, a22, x, y, s, o, begin, end)
                       : slicedNormalRowsAvx2<false>(ss, col, a22, x, y, s, o, begin, end);
#endif
  return store_zeros ? slicedNormalRows<true>(ss, col, a22, x, y, s, o, begin, end)
                     : slicedNormalRows<false>(ss, col, a22, x, y, s, o, begin, end);
}

template <bool Dot>
double BlockMatrix::productViaPlanar(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const int n = n_;
  y.resize(3 * n);
  xs_.resize(3 * static_cast<std::size_t>(n));
  ys_.resize(3 * static_cast<std::size_t>(n));
  double dot = 0;
#pragma omp parallel reduction(+ : dot) if (n > kParallelNodes)
  {
    const auto [b, e] = core::threadRange(n);
    toPlanar(x.data(), xs_.data(), n, b, e);
#pragma omp barrier
    const double d = multiplyPlanar(xs_.data(), ys_.data(), b, e);
    if (Dot)
      dot += d;
    fromPlanar(ys_.data(), y.data(), n, b, e);
  }
  return dot;
}

template <bool Dot>
double BlockMatrix::product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // Plain storage, interleaved vectors: each thread its contiguous rows.
  // Split blocks and x without in-plane part (every thread checks its rows):
  // the normal plane alone, the in-plane components of y stored as +0.
  const int n = nodes();
  y.resize(3 * n);
  double dot = 0;
  const bool may_skip = split_ && skipsZeroPlanes();
  int inplane = 0; // threads that found an in-plane component not zero
#pragma omp parallel reduction(+ : dot) if (n > kParallelNodes)
  {
    const auto [b, e] = core::threadRange(n);
    bool normal = false;
    if (may_skip) {
      if (!inPlaneZero(x.data(), 3, 1, b, e)) {
#pragma omp atomic
        ++inplane;
      }
#pragma omp barrier
      int found;
#pragma omp atomic read
      found = inplane;
      normal = found == 0;
    }
    const double d = normal ? normalRows(x.data(), y.data(), 3, 1, b, e, true)
                            : plainRows(x.data(), y.data(), 3, 1, b, e);
    if (Dot)
      dot += d;
  }
  return dot;
}

Eigen::Matrix3d BlockMatrix::diagonalBlock(int i) const {
  if (split_) { // slice i / kSlice, lane i % kSlice: the first slot on column i
    const int q = i / kSlice, l = i % kSlice;
    for (int k = start_[q]; k < start_[q + 1]; ++k)
      if (col_[kSlice * static_cast<std::size_t>(k) + l] == i) {
        const double* m = val_.data() + 4 * kSlice * static_cast<std::size_t>(k) + l;
        Eigen::Matrix3d d;
        d << m[0], m[2 * kSlice], 0, m[kSlice], m[3 * kSlice], 0, 0, 0,
            val22_[kSlice * static_cast<std::size_t>(k) + l];
        return d;
      }
    return Eigen::Matrix3d::Zero();
  }
  // Shared rows store column offsets (diagonal = 0), plain rows columns (= i).
  const bool shared = !kind_.empty();
  const int t = shared ? kind_[i] : i;
  const std::vector<int>& start = shared ? kstart_ : start_;
  const std::vector<int>& cols = shared ? koff_ : col_;
  const std::vector<double>& vals = shared ? kval_ : val_;
  const int diagonal = shared ? 0 : i;
  for (int b = start[t]; b < start[t + 1]; ++b)
    if (cols[b] == diagonal) {
      if (shared) // row-major
        return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(vals.data() + 9 * b);
      return Eigen::Map<const Eigen::Matrix3d>(vals.data() + 9 * b); // column-major
    }
  return Eigen::Matrix3d::Zero();
}

} // namespace lamina::membrane
