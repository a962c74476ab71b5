#pragma once
/// @file command_line.hpp
/// @brief The options the programs share (--library, --catalog, --set,
/// --threads, --json, --quiet), declared by one function so that every
/// program and subcommand has the same wording and defaults, accepted
/// before or after a subcommand; and the one report of a command-line
/// error ("PROGRAM: error: MESSAGE (see PROGRAM --help)").

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace lamina::core {

/// The shared options, parsed. A program with subcommands declares them on
/// itself and on each subcommand that takes them, into the same object.
struct SharedOptions {
  std::string library;                ///< --library PATH ("" = the default path)
  std::string catalog;                ///< --catalog PATH ("" = the default path)
  std::vector<std::string> overrides; ///< --set KEY=VALUE, in command-line order
  int threads = 0;                    ///< --threads N (0: automatic)
  bool json = false;                  ///< --json
  bool quiet = false;                 ///< --quiet
};

/// Which of the shared options a program or a subcommand takes (bit set).
enum class Shared : unsigned {
  None = 0,
  Library = 1u << 0, ///< --library
  Catalog = 1u << 1, ///< --catalog
  Set = 1u << 2,     ///< --set KEY=VALUE (repeatable)
  Threads = 1u << 3, ///< --threads N
  Json = 1u << 4,    ///< --json
  Quiet = 1u << 5,   ///< --quiet
};

/// @return the union of @p a and @p b
constexpr Shared operator|(Shared a, Shared b) {
  return static_cast<Shared>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}

/// @return whether @p set holds @p one
constexpr bool takes(Shared set, Shared one) {
  return (static_cast<unsigned>(set) & static_cast<unsigned>(one)) != 0;
}

/// The one wording of the library's default, for help texts and messages:
/// "--library PATH, else $LAMINA_LIBRARY, else ..." (materials::Library::resolvePath).
extern const char* const kLibraryHelp;
/// The one wording of the catalog's default (materials::Catalog::defaultPath).
extern const char* const kCatalogHelp;

/// Declares the shared options in @p which on @p app, into @p o, with the
/// one help text of each (and its default). --set appends to o.overrides,
/// so --set given before and after a subcommand all count, in order.
void addSharedOptions(CLI::App& app, SharedOptions& o, Shared which);

/// Declares the shared options @p which on the program @p app (before a
/// subcommand) and on each subcommand in @p subcommands with the options
/// that subcommand takes (after it); an option given before the subcommand
/// that the subcommand does not take is refused after parsing (a usage
/// error naming the option and the subcommand). Also requires exactly one
/// subcommand.
void addSharedOptions(CLI::App& app, SharedOptions& o,
                      const std::vector<std::pair<CLI::App*, Shared>>& subcommands);

/// Every option's default shown in --help ("[default]" after its text) for
/// the options declared on @p app and its subcommands from now on.
void showDefaults(CLI::App& app);

/// Reports the command-line error @p e of @p program: --help and --version
/// print through CLI11 (exit 0); any other error is one line on stderr,
/// "PROGRAM: error: MESSAGE (see PROGRAM --help)", with one wording for a
/// missing subcommand ("a subcommand is required: one of A, B, C").
/// @return the exit code (0 or kExitUsage)
int reportUsageError(const CLI::App& app, const CLI::ParseError& e, const std::string& program);

} // namespace lamina::core
