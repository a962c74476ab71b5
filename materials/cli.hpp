#pragma once
/// @file cli.hpp
/// @brief The command line of the `materials` program as a function, so
/// that the program and the argument fuzzer run the same parsing and checks.

namespace lamina::materials {

/// Parses @p argv (argv[0] is the program name), runs the subcommand and
/// @return the exit code (kExitOk, kExitUserError, kExitUsage). Every error,
/// whatever its type, is printed on stderr and becomes an exit code: nothing
/// escapes.
int runProgram(int argc, char** argv);

} // namespace lamina::materials
