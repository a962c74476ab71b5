#include "homogenize/fft.hpp"

#include "core/error.hpp"

#include <mutex>
#include <new>

namespace lamina::homogenize {

AlignedBuffer::AlignedBuffer(std::size_t count) : size_(count) {
  double* p = fftw_alloc_real(count > 0 ? count : 1);
  if (!p)
    throw std::bad_alloc();
  data_.reset(p);
}

void AlignedBuffer::Free::operator()(double* p) const { fftw_free(p); }

namespace {
// FFTW's planner is not thread-safe and fftw_init_threads must run once.
std::mutex& plannerMutex() {
  static std::mutex m;
  return m;
}
} // namespace

VectorFft::VectorFft(const Grid& grid, int threads, bool measure) : grid_(grid) {
  std::lock_guard<std::mutex> lock(plannerMutex());
  static const bool threads_ok = fftw_init_threads() != 0;
  if (threads_ok && threads > 0)
    fftw_plan_with_nthreads(threads);
  const std::size_t N = grid.size(), Nc = grid.complexSize();
  work_ = fftw_alloc_complex(3 * Nc);
  AlignedBuffer real(3 * N);
  if (!work_)
    throw std::bad_alloc();
  const int n[3] = {grid.n[0], grid.n[1], grid.n[2]};
  const unsigned flags = measure ? FFTW_MEASURE : FFTW_ESTIMATE;
  r2c_ = fftw_plan_many_dft_r2c(3, n, 3, real.data(), nullptr, 1, static_cast<int>(N), work_,
                                nullptr, 1, static_cast<int>(Nc), flags);
  c2r_ = fftw_plan_many_dft_c2r(3, n, 3, work_, nullptr, 1, static_cast<int>(Nc), real.data(),
                                nullptr, 1, static_cast<int>(N), flags);
  LAMINA_CHECK(r2c_ && c2r_, "FFTW could not plan transforms of ", n[0], "x", n[1], "x", n[2]);
}

VectorFft::~VectorFft() {
  std::lock_guard<std::mutex> lock(plannerMutex());
  if (r2c_)
    fftw_destroy_plan(r2c_);
  if (c2r_)
    fftw_destroy_plan(c2r_);
  fftw_free(work_);
}

void VectorFft::forward(const double* in, fftw_complex* out) const {
  // the plan preserves its input (out-of-place r2c): the cast is safe
  fftw_execute_dft_r2c(r2c_, const_cast<double*>(in), out);
}

void VectorFft::backward(fftw_complex* in, double* out) const { fftw_execute_dft_c2r(c2r_, in, out); }

} // namespace lamina::homogenize
