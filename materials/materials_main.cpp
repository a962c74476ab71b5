/// @file materials_main.cpp
/// @brief The `materials` program (materials/cli.hpp).

#include "core/error.hpp"
#include "materials/cli.hpp"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  try {
    return lamina::materials::runProgram(argc, argv);
  } catch (...) { // runProgram lets nothing escape; this is the last guard
    std::fputs("materials: unexpected error\n", stderr);
    return lamina::kExitUserError;
  }
}
