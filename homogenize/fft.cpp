#include "homogenize/fft.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <new>

namespace lamina::homogenize {

AlignedBuffer::AlignedBuffer(std::size_t count) : size_(count) {
  double* p = fftw_alloc_real(count > 0 ? count : 1);
  if (!p)
    throw std::bad_alloc();
  data_.reset(p);
}

void AlignedBuffer::Free::operator()(double* p) const {
  fftw_free(p);
}

namespace {
// FFTW's planner is not thread-safe and fftw_init_threads must run once.
std::mutex& plannerMutex() {
  static std::mutex m;
  return m;
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

namespace {
// Wisdom is an optimisation only: failures to read or write it are ignored.
void importWisdom(const std::string& path) {
  static bool done = false;
  if (done || path.empty())
    return;
  done = true;
  fftw_import_wisdom_from_filename(path.c_str());
}

void exportWisdom(const std::string& path) {
  if (path.empty())
    return;
  try {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::unique_ptr<char, void (*)(void*)> text(fftw_export_wisdom_to_string(), std::free);
    if (text)
      core::writeFileAtomically(path, text.get());
  } catch (const std::exception&) {
  }
}
} // namespace

VectorFft::VectorFft(const Grid& grid, int threads, bool measure) : grid_(grid) {
  std::lock_guard<std::mutex> lock(plannerMutex());
  static const bool threads_ok = fftw_init_threads() != 0;
  const std::string wisdom = measure ? wisdomPath() : std::string();
  importWisdom(wisdom);
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
  if (measure)
    exportWisdom(wisdom);
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

void VectorFft::backward(fftw_complex* in, double* out) const {
  fftw_execute_dft_c2r(c2r_, in, out);
}

} // namespace lamina::homogenize
