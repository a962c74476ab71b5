#include "core/command_line.hpp"

#include "core/error.hpp"

#include <filesystem>
#include <iostream>

namespace lamina::core {

const char* const kLibraryHelp =
    "materials library file: --library PATH, else $LAMINA_LIBRARY, else "
    "$XDG_DATA_HOME/lamina/library.toml (XDG_DATA_HOME unset: "
    "~/.local/share/lamina/library.toml)";
const char* const kCatalogHelp =
    "catalog of base materials: --catalog PATH, else $LAMINA_CATALOG, else "
    "materials/catalog.toml of the source tree";

namespace {

/// The help texts of the other shared options (one wording everywhere).
constexpr const char* kSetHelp =
    "override a key of the case or cell file, e.g. time.dt=1e-7 or cell.resolution=16 "
    "(repeatable; the value is TOML, a bare word a string)";
constexpr const char* kThreadsHelp = "threads: OpenMP, and FFTW in homogenize (0: automatic)";
constexpr const char* kJsonHelp = "print the result as JSON on stdout (for scripts)";
constexpr const char* kQuietHelp = "no progress line on stderr";

/// The names of the shared options, to tell them from a program's own.
const std::vector<std::pair<Shared, const char*>> kSharedNames = {
    {Shared::Library, "--library"}, {Shared::Catalog, "--catalog"}, {Shared::Set, "--set"},
    {Shared::Threads, "--threads"}, {Shared::Json, "--json"},       {Shared::Quiet, "--quiet"}};

/// Refuses a shared option given before the subcommand (on @p app) that
/// the chosen subcommand does not take.
void checkTakenBySubcommand(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) {
    for (const auto& [bit, name] : kSharedNames) {
      (void)bit;
      const CLI::Option* given = app.get_option_no_throw(name);
      if (given && given->count() > 0 && !sub->get_option_no_throw(name))
        throw CLI::ValidationError(std::string(name) + ": '" +
                                       std::filesystem::path(app.get_name()).filename().string() +
                                       " " + sub->get_name() + "' does not take it",
                                   CLI::ExitCodes::ValidationError);
    }
  }
}

} // namespace

void addSharedOptions(CLI::App& app, SharedOptions& o, Shared which) {
  if (takes(which, Shared::Library))
    app.add_option("--library", o.library, kLibraryHelp)->type_name("PATH");
  if (takes(which, Shared::Catalog))
    app.add_option("--catalog", o.catalog, kCatalogHelp)->type_name("PATH");
  if (takes(which, Shared::Set))
    app.add_option_function<std::vector<std::string>>(
           "--set",
           [&o](const std::vector<std::string>& v) {
             o.overrides.insert(o.overrides.end(), v.begin(), v.end());
           },
           kSetHelp)
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false); // one value per flag, so a positional may follow
  if (takes(which, Shared::Threads))
    app.add_option("--threads", o.threads, kThreadsHelp)
        ->type_name("N")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
  if (takes(which, Shared::Json))
    app.add_flag("--json", o.json, kJsonHelp);
  if (takes(which, Shared::Quiet))
    app.add_flag("--quiet", o.quiet, kQuietHelp);
}

void addSharedOptions(CLI::App& app, SharedOptions& o,
                      const std::vector<std::pair<CLI::App*, Shared>>& subcommands) {
  Shared all = Shared::None;
  for (const auto& [sub, which] : subcommands) {
    addSharedOptions(*sub, o, which);
    all = all | which;
  }
  addSharedOptions(app, o, all);
  app.require_subcommand(1);
  app.final_callback([&app] { checkTakenBySubcommand(app); });
}

void showDefaults(CLI::App& app) {
  app.option_defaults()->always_capture_default();
}

int reportUsageError(const CLI::App& app, const CLI::ParseError& e, const std::string& program) {
  if (e.get_exit_code() == 0) // --help, --help-all: CLI11 prints the text
    return app.exit(e);
  std::string message = e.what();
  const auto all = app.get_subcommands([](const CLI::App*) { return true; });
  if (!all.empty() && app.get_subcommands().empty() && message == "A subcommand is required") {
    message = "a subcommand is required: one of";
    std::string sep = " ";
    for (const CLI::App* sub : all) {
      message += sep + sub->get_name();
      sep = ", ";
    }
  }
  std::cerr << program << ": error: " << message << " (see " << program << " --help)\n";
  return kExitUsage;
}

} // namespace lamina::core
