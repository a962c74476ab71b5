#pragma once
/// @file distribution.hpp
/// @brief How the voxel grid is split over processes: FFTW's MPI slab
/// decomposition along x (each rank owns the x-planes [x0, x0 + nx)), or the
/// whole grid on one process. Also the few collective operations the solver
/// needs: sums over ranks, the halo planes of the stiffness operator and the
/// scatter of the phase map.
///
/// MPI is optional at build time (LAMINA_WITH_MPI); without it, or when the
/// program was not started by mpirun, every Distribution is serial.

#include "homogenize/grid.hpp"

#include <cstdint>
#include <vector>

namespace lamina::homogenize {

/// The x-slab of the grid this process owns and the collectives over ranks.
class Distribution {
public:
  /// The whole grid on this process.
  static Distribution serial(const Grid& grid);
  /// FFTW's slab decomposition over MPI_COMM_WORLD when MPI is initialised
  /// and has more than one rank, else serial(). Every rank must own at
  /// least one x-plane (an error names the largest usable rank count).
  static Distribution world(const Grid& grid);

  /// @return this process's rank (0 when serial)
  int rank() const { return rank_; }
  /// @return the number of ranks (1 when serial)
  int ranks() const { return ranks_; }
  /// @return true with more than one rank
  bool distributed() const { return ranks_ > 1; }
  /// @return the first x-plane owned here
  int x0() const { return x0_; }
  /// @return the number of x-planes owned here
  int nx() const { return nx_; }
  /// @return voxels per x-plane (n1 n2)
  std::size_t planeSize() const { return plane_; }
  /// @return voxels owned here (nx n1 n2)
  std::size_t localSize() const { return static_cast<std::size_t>(nx_) * plane_; }

  /// Sums @p n values in place over all ranks (MPI_Allreduce).
  void sum(double* v, int n) const;
  /// Sums @p n counts in place over all ranks.
  void sum(std::size_t* v, int n) const;
  /// @return the largest of @p v over all ranks
  double max(double v) const;
  /// Periodic halo of @p comps component-major fields of localSize() values
  /// each: @p lo receives plane x0 - 1 and @p hi plane x0 + nx (comps
  /// planes each, component-major). Serial: copies the wrapped planes.
  void exchangeHalo(const double* field, int comps, double* lo, double* hi) const;
  /// Same for float fields (the single-precision cell operator).
  void exchangeHalo(const float* field, int comps, float* lo, float* hi) const;
  /// Same for one int32 field.
  void exchangeHalo(const std::int32_t* field, std::int32_t* lo, std::int32_t* hi) const;
  /// Copies rank 0's @p v (size and values) to every rank (no-op when serial).
  void broadcast(std::vector<double>& v) const;
  /// Rank 0 holds the whole grid's @p global values (C order, x slowest);
  /// every rank gets its slab. Serial: a copy.
  std::vector<std::int32_t> scatter(const std::vector<std::int32_t>& global) const;
  /// Gathers every rank's slab of a component-major field of @p comps
  /// components onto rank 0 (others get an empty vector).
  std::vector<double> gather(const double* local, int comps) const;

private:
  int rank_ = 0, ranks_ = 1, x0_ = 0, nx_ = 0;
  std::size_t plane_ = 0;
  std::vector<int> x0s_, nxs_; // per rank (distributed only)
};

/// MPI for the `homogenize` program: initialises MPI when the process was
/// started by an MPI launcher (and lamina was built with MPI), finalises it
/// on destruction. Otherwise it does nothing and the run is serial.
class MpiSession {
public:
  /// @param argc, argv the program's arguments (MPI_Init may consume some)
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  /// @return this process's rank (0 without MPI)
  int rank() const { return rank_; }
  /// @return the number of ranks (1 without MPI)
  int ranks() const { return ranks_; }
  /// Copies @p bytes at @p data from rank 0 to every rank (no-op when serial).
  void broadcast(void* data, std::size_t bytes) const;
  /// Makes every rank exit with @p code when one rank hit an error
  /// (MPI_Abort under MPI); a no-op returning @p code when serial.
  int abort(int code) const;

private:
  bool active_ = false;
  int rank_ = 0, ranks_ = 1;
};

/// @return true when lamina was built with MPI support
bool builtWithMpi();

} // namespace lamina::homogenize
