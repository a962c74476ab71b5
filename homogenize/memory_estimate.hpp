#pragma once
/// @file memory_estimate.hpp
/// @brief What a linear homogenization holds in memory, so that the program
/// and the Python module refuse a grid that cannot fit before anything
/// large is allocated (docs/homogenize-solver.md, "Memory").

#include "homogenize/homogenizer.hpp"

#include <cstdint>

namespace lamina::homogenize {

/// @return the bytes one rank of @p ranks (rank @p rank) holds during the
/// linear homogenization of @p voxels voxels with @p opt: per voxel the CG
/// vectors, the FFT buffer and the phase index (and with the energy
/// estimate six displacement fields), split over the ranks; rank 0 also
/// holds the whole phase map and, for a cell with a size (@p has_size),
/// the spectra of the dispersion tensor.
double linearSolveBytes(std::uint64_t voxels, const Options& opt, bool has_size, int ranks = 1,
                        int rank = 0);

/// @return true when @p opt runs the cell operator and the CG vectors in
/// float (its precision, or autoPrecision(tol) when unset; see floatVectors())
bool singleVectors(const Options& opt);

} // namespace lamina::homogenize
