#include "homogenize/fftw_threads.hpp"

#include <fftw3.h>

namespace lamina::homogenize {

bool initFftwThreads() {
  static const bool ok = fftw_init_threads() != 0 && fftwf_init_threads() != 0;
  return ok;
}

} // namespace lamina::homogenize
