/// @file main.cpp
/// @brief The `homogenize` program (homogenize/cli.hpp), serial or under
/// `mpirun -np N`.

#include "core/error.hpp"
#include "homogenize/cli.hpp"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  try {
    lamina::homogenize::MpiSession mpi(&argc, &argv);
    return lamina::homogenize::runProgram(argc, argv, mpi);
  } catch (const std::exception& e) { // MPI start-up; runProgram lets nothing escape
    std::fprintf(stderr, "homogenize: %s\n", e.what());
  } catch (...) {
    std::fputs("homogenize: unexpected error\n", stderr);
  }
  return lamina::kExitUserError;
}
