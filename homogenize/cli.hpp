#pragma once
/// @file cli.hpp
/// @brief The command line of the `homogenize` program as a function, so
/// that the program and the argument fuzzer run the same parsing and checks.

#include "core/error.hpp"
#include "homogenize/distribution.hpp"

namespace lamina::homogenize {

/// Parses @p argv (argv[0] is the program name), checks the options, reads
/// and builds the cell and runs (linear into the library, or nonlinear);
/// @return the exit code (kExitOk, kExitUserError, kExitUsage,
/// kExitDivergence). Every error is printed on stderr and becomes an exit
/// code (through @p mpi's abort under MPI); one that is not a lamina::Error
/// or a command-line error is rethrown instead when @p unexpected is
/// Rethrow.
int runProgram(int argc, char** argv, MpiSession& mpi,
               UnexpectedErrors unexpected = UnexpectedErrors::Report);

} // namespace lamina::homogenize
