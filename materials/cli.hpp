#pragma once
/// @file cli.hpp
/// @brief The command line of the `materials` program as a function, so
/// that the program and the argument fuzzer run the same parsing and checks.

#include "core/error.hpp"

namespace lamina::materials {

/// Parses @p argv (argv[0] is the program name), runs the subcommand and
/// @return the exit code (kExitOk, kExitUserError, kExitUsage). Every error
/// is printed on stderr and becomes an exit code; one that is not a
/// lamina::Error or a command-line error is rethrown instead when
/// @p unexpected is Rethrow.
int runProgram(int argc, char** argv, UnexpectedErrors unexpected = UnexpectedErrors::Report);

} // namespace lamina::materials
