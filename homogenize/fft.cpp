#include "homogenize/fft.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "homogenize/fftw_threads.hpp"

#include <fftw3.h>
#include <omp.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <new>
#include <sys/mman.h>
#include <type_traits>

#ifdef LAMINA_WITH_MPI
#include <fftw3-mpi.h>
#endif

namespace lamina::homogenize {

namespace {
void* allocateField(std::size_t bytes) {
  // Fields of 2 MiB and more start on a 2 MiB boundary and are offered to
  // the kernel's transparent huge pages (used where THP is "madvise", the
  // Debian default): one page fault per 2 MiB instead of per 4 KiB when a
  // field is first written (a 128^3 run allocates about 0.5 GB), and fewer
  // TLB misses in the transforms' strided passes. Smaller ones are 64-byte
  // aligned (FFTW's SIMD alignment and more).
  constexpr std::size_t kHuge = std::size_t(2) << 20;
  void* p = nullptr;
  if (posix_memalign(&p, bytes >= kHuge ? kHuge : 64, bytes > 0 ? bytes : 1) != 0 || !p)
    throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  if (bytes >= kHuge)
    madvise(p, bytes - bytes % kHuge, MADV_HUGEPAGE); // advice only: errors are harmless
#endif
  return p;
}

void freeField(void* p) {
  std::free(p);
}
} // namespace

template <class T>
AlignedArray<T>::AlignedArray(std::size_t count)
    : data_(static_cast<T*>(allocateField(count * sizeof(T)))), size_(count) {}

template <class T>
void AlignedArray<T>::Free::operator()(T* p) const {
  freeField(p);
}

template class AlignedArray<double>;
template class AlignedArray<float>;

namespace {
// FFTW's planner is not thread-safe and fftw_init_threads must run once.
std::mutex& plannerMutex() {
  static std::mutex m;
  return m;
}

// The three components in one serial plan (howmany = 3): in place, each a
// chunk of @p dist complex entries apart, its real rows padded to 2 (n2/2+1).
struct Batch {
  Batch(const Grid& g, int dist)
      : real{g.n[0], g.n[1], 2 * (g.n[2] / 2 + 1)}, modes{g.n[0], g.n[1], g.n[2] / 2 + 1},
        real_dist(2 * dist) {}
  int real[3], modes[3]; ///< embedding of the real and the complex arrays
  int real_dist;         ///< reals between components
};

// The FFTW calls of one precision behind one name.
template <class T>
struct Fftw;
template <>
struct Fftw<double> {
  using Plan = fftw_plan;
  using Complex = fftw_complex;
  static void threads(int n) { fftw_plan_with_nthreads(n); }
  static Plan manyR2c(const Grid& g, double* in, Complex* out, int dist, unsigned flags) {
    const Batch b(g, dist);
    return fftw_plan_many_dft_r2c(3, g.n.data(), 3, in, b.real, 1, b.real_dist, out, b.modes, 1,
                                  dist, flags);
  }
  static Plan manyC2r(const Grid& g, Complex* in, double* out, int dist, unsigned flags) {
    const Batch b(g, dist);
    return fftw_plan_many_dft_c2r(3, g.n.data(), 3, in, b.modes, 1, dist, out, b.real, 1,
                                  b.real_dist, flags);
  }
#ifdef LAMINA_WITH_MPI
  static Plan mpiR2c(const Grid& g, double* in, Complex* out, unsigned flags) {
    return fftw_mpi_plan_dft_r2c_3d(g.n[0], g.n[1], g.n[2], in, out, MPI_COMM_WORLD, flags);
  }
  static Plan mpiC2r(const Grid& g, Complex* in, double* out, unsigned flags) {
    return fftw_mpi_plan_dft_c2r_3d(g.n[0], g.n[1], g.n[2], in, out, MPI_COMM_WORLD, flags);
  }
  static std::ptrdiff_t localSize(const Grid& g) {
    ptrdiff_t n0 = 0, s0 = 0;
    return fftw_mpi_local_size_3d(g.n[0], g.n[1], g.n[2] / 2 + 1, MPI_COMM_WORLD, &n0, &s0);
  }
  static void execR2c(Plan p, double* in, Complex* out) {
    fftw_mpi_execute_dft_r2c(p, in, out);
  }
  static void execC2r(Plan p, Complex* in, double* out) {
    fftw_mpi_execute_dft_c2r(p, in, out);
  }
  static void gatherWisdom() {
    fftw_mpi_gather_wisdom(MPI_COMM_WORLD);
  }
  static void broadcastWisdom() {
    fftw_mpi_broadcast_wisdom(MPI_COMM_WORLD);
  }
#endif
  static void serialR2c(Plan p, double* in, Complex* out) {
    fftw_execute_dft_r2c(p, in, out);
  }
  static void serialC2r(Plan p, Complex* in, double* out) {
    fftw_execute_dft_c2r(p, in, out);
  }
  static void destroy(Plan p) {
    fftw_destroy_plan(p);
  }
  static void importWisdom(const char* path) {
    fftw_import_wisdom_from_filename(path);
  }
  static char* exportWisdom() {
    return fftw_export_wisdom_to_string();
  }
  static const char* suffix() {
    return "";
  }
};
template <>
struct Fftw<float> {
  using Plan = fftwf_plan;
  using Complex = fftwf_complex;
  static void threads(int n) { fftwf_plan_with_nthreads(n); }
  static Plan manyR2c(const Grid& g, float* in, Complex* out, int dist, unsigned flags) {
    const Batch b(g, dist);
    return fftwf_plan_many_dft_r2c(3, g.n.data(), 3, in, b.real, 1, b.real_dist, out, b.modes, 1,
                                   dist, flags);
  }
  static Plan manyC2r(const Grid& g, Complex* in, float* out, int dist, unsigned flags) {
    const Batch b(g, dist);
    return fftwf_plan_many_dft_c2r(3, g.n.data(), 3, in, b.modes, 1, dist, out, b.real, 1,
                                   b.real_dist, flags);
  }
#ifdef LAMINA_WITH_MPI
  static Plan mpiR2c(const Grid& g, float* in, Complex* out, unsigned flags) {
    return fftwf_mpi_plan_dft_r2c_3d(g.n[0], g.n[1], g.n[2], in, out, MPI_COMM_WORLD, flags);
  }
  static Plan mpiC2r(const Grid& g, Complex* in, float* out, unsigned flags) {
    return fftwf_mpi_plan_dft_c2r_3d(g.n[0], g.n[1], g.n[2], in, out, MPI_COMM_WORLD, flags);
  }
  static std::ptrdiff_t localSize(const Grid& g) {
    ptrdiff_t n0 = 0, s0 = 0;
    return fftwf_mpi_local_size_3d(g.n[0], g.n[1], g.n[2] / 2 + 1, MPI_COMM_WORLD, &n0, &s0);
  }
  static void execR2c(Plan p, float* in, Complex* out) {
    fftwf_mpi_execute_dft_r2c(p, in, out);
  }
  static void execC2r(Plan p, Complex* in, float* out) {
    fftwf_mpi_execute_dft_c2r(p, in, out);
  }
  static void gatherWisdom() {
    fftwf_mpi_gather_wisdom(MPI_COMM_WORLD);
  }
  static void broadcastWisdom() {
    fftwf_mpi_broadcast_wisdom(MPI_COMM_WORLD);
  }
#endif
  static void serialR2c(Plan p, float* in, Complex* out) {
    fftwf_execute_dft_r2c(p, in, out);
  }
  static void serialC2r(Plan p, Complex* in, float* out) {
    fftwf_execute_dft_c2r(p, in, out);
  }
  static void destroy(Plan p) {
    fftwf_destroy_plan(p);
  }
  static void importWisdom(const char* path) {
    fftwf_import_wisdom_from_filename(path);
  }
  static char* exportWisdom() {
    return fftwf_export_wisdom_to_string();
  }
  static const char* suffix() {
    return "-single";
  }
};

// Wisdom is an optimisation only: failures to read or write it are ignored.
template <class T>
void importWisdom(const std::string& path) {
  static bool done = false;
  if (done || path.empty())
    return;
  done = true;
  Fftw<T>::importWisdom(path.c_str());
}

template <class T>
void exportWisdom(const std::string& path) {
  if (path.empty())
    return;
  try {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::unique_ptr<char, void (*)(void*)> text(Fftw<T>::exportWisdom(), std::free);
    if (text)
      core::writeFileAtomically(path, text.get());
  } catch (const std::exception&) {
  }
}
} // namespace

std::string VectorFft::wisdomPath() {
  if (const char* p = std::getenv("LAMINA_FFTW_WISDOM"))
    return p;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    return std::string(x) + "/lamina/fftw-wisdom";
  if (const char* h = std::getenv("HOME"); h && *h)
    return std::string(h) + "/.cache/lamina/fftw-wisdom";
  return "";
}

// One precision's plans: one in-place r2c and one c2r plan for a single
// component, executed on each of the three chunks (new-array execute: the
// chunks are equally aligned).
struct VectorFft::Plans {
  virtual ~Plans() = default;
  virtual void forward(void* buffer, std::size_t chunk) = 0;
  virtual void backward(void* buffer, std::size_t chunk) = 0;
};

namespace {
template <class T>
struct PlansOf : VectorFft::Plans {
  using F = Fftw<T>;
  typename F::Plan r2c = nullptr, c2r = nullptr;
  bool mpi = false;
  bool batched = false; // serial: one plan for the three components
  ~PlansOf() override {
    if (r2c)
      F::destroy(r2c);
    if (c2r)
      F::destroy(c2r);
  }
  static T* real(void* buffer, std::size_t chunk, int c) {
    return reinterpret_cast<T*>(static_cast<typename F::Complex*>(buffer) + c * chunk);
  }
  static typename F::Complex* modes(void* buffer, std::size_t chunk, int c) {
    return static_cast<typename F::Complex*>(buffer) + c * chunk;
  }
  void forward(void* buffer, std::size_t chunk) override {
    if (batched) {
      F::serialR2c(r2c, real(buffer, chunk, 0), modes(buffer, chunk, 0));
      return;
    }
    for (int c = 0; c < 3; ++c) {
#ifdef LAMINA_WITH_MPI
      if (mpi) {
        F::execR2c(r2c, real(buffer, chunk, c), modes(buffer, chunk, c));
        continue;
      }
#endif
      F::serialR2c(r2c, real(buffer, chunk, c), modes(buffer, chunk, c));
    }
  }
  void backward(void* buffer, std::size_t chunk) override {
    if (batched) {
      F::serialC2r(c2r, modes(buffer, chunk, 0), real(buffer, chunk, 0));
      return;
    }
    for (int c = 0; c < 3; ++c) {
#ifdef LAMINA_WITH_MPI
      if (mpi) {
        F::execC2r(c2r, modes(buffer, chunk, c), real(buffer, chunk, c));
        continue;
      }
#endif
      F::serialC2r(c2r, modes(buffer, chunk, c), real(buffer, chunk, c));
    }
  }
};

template <class T>
std::unique_ptr<VectorFft::Plans> makePlans(const Grid& grid, const Distribution& dist, int threads,
                                            bool measure, void*& buffer, std::size_t& chunk) {
  using F = Fftw<T>;
  auto plans = std::make_unique<PlansOf<T>>();
  plans->mpi = dist.distributed();
  std::string wisdom = measure ? VectorFft::wisdomPath() : std::string();
  if (!wisdom.empty()) {
    wisdom += F::suffix();
    if (dist.distributed())
      wisdom += "-mpi" + std::to_string(dist.ranks());
  }
  chunk = static_cast<std::size_t>(dist.nx()) * static_cast<std::size_t>(grid.n[1]) *
          static_cast<std::size_t>(grid.n[2] / 2 + 1);
#ifdef LAMINA_WITH_MPI
  if (dist.distributed())
    chunk = std::max(chunk, static_cast<std::size_t>(F::localSize(grid)));
#endif
  chunk += chunk % 2; // keeps every chunk 16-byte aligned in single precision too
  buffer = allocateField(3 * chunk * 2 * sizeof(T));
  if (threads > 0)
    F::threads(threads);
  const unsigned flags = measure ? FFTW_MEASURE : FFTW_ESTIMATE;
  T* in = PlansOf<T>::real(buffer, chunk, 0);
  auto* out = PlansOf<T>::modes(buffer, chunk, 0);
  if (dist.distributed()) {
#ifdef LAMINA_WITH_MPI
    // rank 0 reads the wisdom and shares it; plans are made collectively
    if (dist.rank() == 0)
      importWisdom<T>(wisdom);
    F::broadcastWisdom();
    plans->r2c = F::mpiR2c(grid, in, out, flags);
    plans->c2r = F::mpiC2r(grid, out, in, flags);
    F::gatherWisdom();
    if (measure && dist.rank() == 0)
      exportWisdom<T>(wisdom);
#endif
  } else {
    importWisdom<T>(wisdom);
    plans->batched = true;
    const int dist_c = static_cast<int>(chunk);
    plans->r2c = F::manyR2c(grid, in, out, dist_c, flags);
    plans->c2r = F::manyC2r(grid, out, in, dist_c, flags);
    if (measure)
      exportWisdom<T>(wisdom);
  }
  LAMINA_CHECK(plans->r2c && plans->c2r, "FFTW could not plan transforms of ", grid.n[0], "x",
               grid.n[1], "x", grid.n[2]);
  return plans;
}

} // namespace

VectorFft::VectorFft(const Grid& grid, const Distribution& dist, int threads, bool measure,
                     Precision precision)
    : grid_(grid), dist_(dist), precision_(precision) {
  std::lock_guard<std::mutex> lock(plannerMutex());
  const int nthreads = initFftwThreads() ? threads : 0;
  if (precision == Precision::Single)
    plans_ = makePlans<float>(grid, dist, nthreads, measure, buffer_, chunk_);
  else
    plans_ = makePlans<double>(grid, dist, nthreads, measure, buffer_, chunk_);
}

VectorFft::~VectorFft() {
  std::lock_guard<std::mutex> lock(plannerMutex());
  plans_.reset();
  freeField(buffer_);
}

template <>
double* VectorFft::spectrum<double>() const {
  LAMINA_CHECK(precision_ == Precision::Double, "spectrum<double> of a single-precision FFT");
  return static_cast<double*>(buffer_);
}

template <>
float* VectorFft::spectrum<float>() const {
  LAMINA_CHECK(precision_ == Precision::Single, "spectrum<float> of a double-precision FFT");
  return static_cast<float*>(buffer_);
}

// Calls f(row, offset) for every real row of the spectrum buffer (row: its
// n2 values, padded to 2 (n2/2+1); offset: the same row's index in an
// unpadded component-major local field), in parallel.
template <class F>
void VectorFft::eachRow(F&& f) {
  const int n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t rows = static_cast<std::size_t>(dist_.nx()) * n1;
  const std::size_t L = rows * n2, padded = 2 * static_cast<std::size_t>(n2 / 2 + 1);
  auto run = [&](auto* buf) {
#pragma omp parallel for schedule(static) collapse(2)
    for (int c = 0; c < 3; ++c)
      for (std::size_t row = 0; row < rows; ++row)
        f(buf + 2 * c * chunk_ + row * padded, c * L + row * n2);
  };
  if (precision_ == Precision::Single)
    run(spectrum<float>());
  else
    run(spectrum<double>());
}

template <class V>
void VectorFft::forward(const V* r) {
  const int n2 = grid_.n[2];
  eachRow([&](auto* dst, std::size_t off) {
    using T = std::remove_pointer_t<decltype(dst)>;
    for (int k = 0; k < n2; ++k)
      dst[k] = static_cast<T>(r[off + k]);
  });
  plans_->forward(buffer_, chunk_);
}

template <class V>
void VectorFft::forwardUpdate(V* r, double alpha, const V* w) {
  const int n2 = grid_.n[2];
  const V a = static_cast<V>(alpha);
  eachRow([&](auto* dst, std::size_t off) {
    using T = std::remove_pointer_t<decltype(dst)>;
    V* ro = r + off;
    const V* wo = w + off;
    for (int k = 0; k < n2; ++k) {
      const V v = ro[k] - a * wo[k];
      ro[k] = v;
      dst[k] = static_cast<T>(v);
    }
  });
  plans_->forward(buffer_, chunk_);
}

template <class V>
void VectorFft::backward(V* z) {
  const int n2 = grid_.n[2];
  plans_->backward(buffer_, chunk_);
  eachRow([&](auto* src, std::size_t off) {
    for (int k = 0; k < n2; ++k)
      z[off + k] = static_cast<V>(src[k]);
  });
}

template <class V>
void VectorFft::backwardUpdate(V* p, double beta, V* x, double alpha) {
  const int n2 = grid_.n[2];
  const V a = static_cast<V>(alpha), b = static_cast<V>(beta);
  plans_->backward(buffer_, chunk_);
  eachRow([&](auto* src, std::size_t off) {
    V* po = p + off;
    if (x) { // x += alpha p with the old p, read here anyway
      V* xo = x + off;
      for (int k = 0; k < n2; ++k) {
        const V pk = po[k];
        xo[k] += a * pk;
        po[k] = static_cast<V>(src[k]) + b * pk;
      }
      return;
    }
    for (int k = 0; k < n2; ++k)
      po[k] = static_cast<V>(src[k]) + b * po[k];
  });
}

// double fields (double-precision solves, the nonlinear solver, the
// dispersion tensor) and float fields (single-precision linear solves)
#define LAMINA_FFT_FIELDS(V)                                                                       \
  template void VectorFft::forward<V>(const V*);                                                   \
  template void VectorFft::forwardUpdate<V>(V*, double, const V*);                                 \
  template void VectorFft::backward<V>(V*);                                                        \
  template void VectorFft::backwardUpdate<V>(V*, double, V*, double);
LAMINA_FFT_FIELDS(double)
LAMINA_FFT_FIELDS(float)
#undef LAMINA_FFT_FIELDS

} // namespace lamina::homogenize
