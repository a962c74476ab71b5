#include "homogenize/distribution.hpp"

#include "core/error.hpp"
#include "homogenize/fftw_threads.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#ifdef LAMINA_WITH_MPI
#include <fftw3-mpi.h>
#include <mpi.h>
#endif

namespace lamina::homogenize {

namespace {
#ifdef LAMINA_WITH_MPI
bool mpiRunning() {
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  return init && !fin;
}
#endif
} // namespace

bool builtWithMpi() {
#ifdef LAMINA_WITH_MPI
  return true;
#else
  return false;
#endif
}

Distribution Distribution::serial(const Grid& grid) {
  Distribution d;
  d.nx_ = grid.n[0];
  d.plane_ = static_cast<std::size_t>(grid.n[1]) * static_cast<std::size_t>(grid.n[2]);
  return d;
}

Distribution Distribution::world(const Grid& grid) {
  Distribution d = serial(grid);
#ifdef LAMINA_WITH_MPI
  if (!mpiRunning())
    return d;
  MPI_Comm_rank(MPI_COMM_WORLD, &d.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &d.ranks_);
  if (d.ranks_ == 1)
    return d;
  // FFTW decides the slabs (blocks of ceil(n0 / ranks) planes); the real
  // and complex arrays of an r2c transform share them
  ptrdiff_t local_n0 = 0, local_0_start = 0;
  fftw_mpi_local_size_3d(grid.n[0], grid.n[1], grid.n[2] / 2 + 1, MPI_COMM_WORLD, &local_n0,
                         &local_0_start);
  d.nx_ = static_cast<int>(local_n0);
  d.x0_ = static_cast<int>(local_0_start);
  d.x0s_.resize(static_cast<std::size_t>(d.ranks_));
  d.nxs_.resize(static_cast<std::size_t>(d.ranks_));
  MPI_Allgather(&d.x0_, 1, MPI_INT, d.x0s_.data(), 1, MPI_INT, MPI_COMM_WORLD);
  MPI_Allgather(&d.nx_, 1, MPI_INT, d.nxs_.data(), 1, MPI_INT, MPI_COMM_WORLD);
  const int block = (grid.n[0] + d.ranks_ - 1) / d.ranks_;
  const int usable = (grid.n[0] + block - 1) / block;
  LAMINA_CHECK(*std::min_element(d.nxs_.begin(), d.nxs_.end()) > 0, "a grid of ", grid.n[0],
               " x-planes gives some of the ", d.ranks_, " MPI ranks no plane: use at most ",
               usable - (usable == d.ranks_ ? 1 : 0), " ranks");
#endif
  return d;
}

void Distribution::sum(double* v, int n) const {
#ifdef LAMINA_WITH_MPI
  if (distributed())
    MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
#else
  (void)v;
  (void)n;
#endif
}

void Distribution::sum(std::size_t* v, int n) const {
#ifdef LAMINA_WITH_MPI
  static_assert(sizeof(std::size_t) == sizeof(unsigned long long), "size_t is 64-bit");
  if (distributed())
    MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
#else
  (void)v;
  (void)n;
#endif
}

double Distribution::max(double v) const {
#ifdef LAMINA_WITH_MPI
  if (distributed())
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
#endif
  return v;
}

namespace {
// plane p (local index) of component c
template <class T>
const T* planeOf(const T* field, std::size_t local, std::size_t plane, int c, int p) {
  return field + static_cast<std::size_t>(c) * local + static_cast<std::size_t>(p) * plane;
}
} // namespace

namespace {
#ifdef LAMINA_WITH_MPI
template <class T>
MPI_Datatype mpiType();
template <>
MPI_Datatype mpiType<double>() {
  return MPI_DOUBLE;
}
template <>
MPI_Datatype mpiType<float>() {
  return MPI_FLOAT;
}
#endif

// exchangeHalo of double or float fields
template <class T>
void exchangeHaloOf(const Distribution& d, const T* field, int comps, T* lo, T* hi) {
  const std::size_t L = d.localSize(), plane = d.planeSize();
  const int nx = d.nx();
  if (!d.distributed()) {
    for (int c = 0; c < comps; ++c) {
      std::memcpy(lo + c * plane, planeOf(field, L, plane, c, nx - 1), plane * sizeof(T));
      std::memcpy(hi + c * plane, planeOf(field, L, plane, c, 0), plane * sizeof(T));
    }
    return;
  }
#ifdef LAMINA_WITH_MPI
  const int prev = (d.rank() + d.ranks() - 1) % d.ranks(), next = (d.rank() + 1) % d.ranks();
  std::vector<T> first(comps * plane), last(comps * plane);
  for (int c = 0; c < comps; ++c) {
    std::memcpy(first.data() + c * plane, planeOf(field, L, plane, c, 0), plane * sizeof(T));
    std::memcpy(last.data() + c * plane, planeOf(field, L, plane, c, nx - 1), plane * sizeof(T));
  }
  const int count = static_cast<int>(comps * plane);
  // my last plane is the next rank's lo; my first plane is the previous rank's hi
  MPI_Sendrecv(last.data(), count, mpiType<T>(), next, 1, lo, count, mpiType<T>(), prev, 1,
               MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Sendrecv(first.data(), count, mpiType<T>(), prev, 2, hi, count, mpiType<T>(), next, 2,
               MPI_COMM_WORLD, MPI_STATUS_IGNORE);
#endif
}
} // namespace

void Distribution::exchangeHalo(const double* field, int comps, double* lo, double* hi) const {
  exchangeHaloOf(*this, field, comps, lo, hi);
}

void Distribution::exchangeHalo(const float* field, int comps, float* lo, float* hi) const {
  exchangeHaloOf(*this, field, comps, lo, hi);
}

void Distribution::exchangeHalo(const std::int32_t* field, std::int32_t* lo,
                                std::int32_t* hi) const {
  const std::size_t L = localSize();
  if (!distributed()) {
    std::memcpy(lo, planeOf(field, L, plane_, 0, nx_ - 1), plane_ * sizeof(std::int32_t));
    std::memcpy(hi, planeOf(field, L, plane_, 0, 0), plane_ * sizeof(std::int32_t));
    return;
  }
#ifdef LAMINA_WITH_MPI
  const int prev = (rank_ + ranks_ - 1) % ranks_, next = (rank_ + 1) % ranks_;
  const int count = static_cast<int>(plane_);
  MPI_Sendrecv(planeOf(field, L, plane_, 0, nx_ - 1), count, MPI_INT32_T, next, 3, lo, count,
               MPI_INT32_T, prev, 3, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Sendrecv(planeOf(field, L, plane_, 0, 0), count, MPI_INT32_T, prev, 4, hi, count, MPI_INT32_T,
               next, 4, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
#endif
}

void Distribution::broadcast(std::vector<double>& v) const {
#ifdef LAMINA_WITH_MPI
  if (!distributed())
    return;
  unsigned long long n = v.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  v.resize(n);
  MPI_Bcast(v.data(), static_cast<int>(n), MPI_DOUBLE, 0, MPI_COMM_WORLD);
#else
  (void)v;
#endif
}

std::vector<std::int32_t> Distribution::scatter(const std::vector<std::int32_t>& global) const {
  if (!distributed())
    return global;
  std::vector<std::int32_t> local(localSize());
#ifdef LAMINA_WITH_MPI
  // counts can exceed int at 1024^3 over few ranks: send plane by plane
  // blocks of at most 2^30 values
  if (rank_ == 0) {
    for (int r = 0; r < ranks_; ++r) {
      const std::size_t begin = static_cast<std::size_t>(x0s_[r]) * plane_;
      const std::size_t count = static_cast<std::size_t>(nxs_[r]) * plane_;
      if (r == 0) {
        std::copy(global.begin() + static_cast<std::ptrdiff_t>(begin),
                  global.begin() + static_cast<std::ptrdiff_t>(begin + count), local.begin());
        continue;
      }
      for (std::size_t off = 0; off < count; off += (1u << 30)) {
        const std::size_t m = std::min<std::size_t>(1u << 30, count - off);
        MPI_Send(global.data() + begin + off, static_cast<int>(m), MPI_INT32_T, r, 5,
                 MPI_COMM_WORLD);
      }
    }
  } else {
    for (std::size_t off = 0; off < local.size(); off += (1u << 30)) {
      const std::size_t m = std::min<std::size_t>(1u << 30, local.size() - off);
      MPI_Recv(local.data() + off, static_cast<int>(m), MPI_INT32_T, 0, 5, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
    }
  }
#endif
  return local;
}

std::vector<double> Distribution::gather(const double* local, int comps) const {
  const std::size_t L = localSize();
  if (!distributed())
    return std::vector<double>(local, local + comps * L);
  std::vector<double> global;
#ifdef LAMINA_WITH_MPI
  const std::size_t N = static_cast<std::size_t>(x0s_.back() + nxs_.back()) * plane_;
  if (rank_ == 0)
    global.resize(comps * N);
  for (int c = 0; c < comps; ++c) {
    if (rank_ != 0) {
      for (std::size_t off = 0; off < L; off += (1u << 30))
        MPI_Send(local + c * L + off, static_cast<int>(std::min<std::size_t>(1u << 30, L - off)),
                 MPI_DOUBLE, 0, 6, MPI_COMM_WORLD);
      continue;
    }
    for (int r = 0; r < ranks_; ++r) {
      double* dst = global.data() + c * N + static_cast<std::size_t>(x0s_[r]) * plane_;
      const std::size_t count = static_cast<std::size_t>(nxs_[r]) * plane_;
      if (r == 0) {
        std::copy(local + c * L, local + c * L + L, dst);
        continue;
      }
      for (std::size_t off = 0; off < count; off += (1u << 30))
        MPI_Recv(dst + off, static_cast<int>(std::min<std::size_t>(1u << 30, count - off)),
                 MPI_DOUBLE, r, 6, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
  }
#endif
  return global;
}

MpiSession::MpiSession(int* argc, char*** argv) {
#ifdef LAMINA_WITH_MPI
  // Only under a launcher: a serial run never touches MPI (Open MPI's
  // singleton start would spawn a daemon and refuses to run as root in CI).
  const bool launched = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") ||
                        std::getenv("PMIX_RANK") || std::getenv("MPI_LOCALNRANKS");
  if (!launched)
    return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  initFftwThreads(); // before fftw_mpi_init (FFTW manual, 6.11)
  fftw_mpi_init();
  fftwf_mpi_init();
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
#else
  (void)argc;
  (void)argv;
#endif
}

MpiSession::~MpiSession() {
#ifdef LAMINA_WITH_MPI
  if (active_)
    MPI_Finalize();
#else
  (void)active_; // set only under MPI
#endif
}

void MpiSession::broadcast(void* data, std::size_t bytes) const {
#ifdef LAMINA_WITH_MPI
  if (active_ && ranks_ > 1)
    MPI_Bcast(data, static_cast<int>(bytes), MPI_BYTE, 0, MPI_COMM_WORLD);
#else
  (void)data;
  (void)bytes;
#endif
}

int MpiSession::abort(int code) const {
#ifdef LAMINA_WITH_MPI
  if (active_ && ranks_ > 1)
    MPI_Abort(MPI_COMM_WORLD, code);
#endif
  return code;
}

} // namespace lamina::homogenize
