/// @file cli.cpp
/// @brief The `materials` program: list, show, add, layup, export, remove, drive.

#include "materials/cli.hpp"

#include "core/atomic_file.hpp"
#include "core/command_line.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "materials/catalog.hpp"
#include "materials/entries.hpp"
#include "materials/export.hpp"
#include "materials/layup.hpp"
#include "materials/library.hpp"
#include "materials/material_source.hpp"
#include "materials/point_driver.hpp"
#include "materials/symmetry.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace mat = lamina::materials;

namespace {

/// @return a provenance value as a person reads it: numbers with 6
/// significant digits (the library file keeps every digit), arrays element
/// by element, anything else as TOML writes it
std::string provenanceText(const toml::node& v) {
  if (const auto* x = v.as_floating_point())
    return lamina::core::formatShort(x->get());
  if (const auto* a = v.as_array()) {
    std::string out;
    for (const toml::node& item : *a)
      out += (out.empty() ? "" : ", ") + provenanceText(item);
    return "[" + out + "]";
  }
  std::ostringstream os;
  v.visit([&os](const auto& x) { os << x; });
  return os.str();
}

/// `show`'s screen. Every stiffness and modulus is in GPa (said on each of
/// their lines), densities in kg/m^3, lengths in m.
void printHuman(const mat::Material& m) {
  const mat::Symmetry s = mat::classify(m.C);
  const mat::EngineeringConstants e = m.C.engineering();
  auto g = [](double x) { return lamina::core::formatShort(x, 6); };
  auto gpa = [](double x) { return lamina::core::formatShort(x * 1e-9, 6); };
  std::cout << m.name << "  (" << m.kind << ")\n"
            << "  density   " << g(m.density) << " kg/m^3\n";
  if (m.thickness)
    std::cout << "  thickness " << g(*m.thickness) << " m\n";
  std::cout << "  symmetry  " << mat::toString(s.cls)
            << (s.axis >= 0 ? std::string(" (axis ") + "xyz"[s.axis] + ")" : "")
            << ", anisotropy index A^U = " << g(mat::anisotropyIndex(m.C)) << "\n"
            << "  C (GPa, lamina order xx yy zz xy yz xz):\n";
  std::cout << lamina::core::formatMatrix6(m.C, 1e-9, 5, 11, "   ");
  std::cout << "  E1 " << gpa(e.E1) << "  E2 " << gpa(e.E2) << "  E3 " << gpa(e.E3) << " GPa\n"
            << "  G12 " << gpa(e.G12) << "  G23 " << gpa(e.G23) << "  G13 " << gpa(e.G13)
            << " GPa\n"
            << "  nu12 " << g(e.nu12) << "  nu13 " << g(e.nu13) << "  nu23 " << g(e.nu23) << "\n";
  if (m.cell_size)
    std::cout << "  cell size " << g((*m.cell_size)[0]) << " x " << g((*m.cell_size)[1]) << " x "
              << g((*m.cell_size)[2]) << " m\n";
  if (m.dispersion) {
    std::cout << "  dispersion zeta^2 D (kg/m, lamina order; micro-inertia, eq. 35):\n";
    std::cout << lamina::core::formatMatrix6(*m.dispersion, 1.0, 4, 11, "   ");
    // omega^2 = c^2 k^2 / (1 + l^2 k^2) for a wave straining component I alone
    const auto l = mat::dispersionLengths(m);
    std::cout << "  characteristic length sqrt(zeta^2 D_II / rho) (m): xx " << g(l[0]) << "  yy "
              << g(l[1]) << "  zz " << g(l[2]) << "  xy " << g(l[3]) << "  yz " << g(l[4])
              << "  xz " << g(l[5]) << "\n";
  }
  for (const mat::Ply& p : m.plies)
    std::cout << "  ply " << p.material << " at " << g(p.angle_deg) << " deg, " << g(p.thickness)
              << " m\n";
  if (!m.side_file.empty())
    std::cout << "  side file " << m.side_file << "\n";
  if (!m.side_checksum.empty())
    std::cout << "  side checksum " << m.side_checksum << "\n";
  if (!m.provenance.empty()) {
    std::cout << "  provenance:\n";
    for (const auto& [k, v] : m.provenance) {
      std::string text = provenanceText(v);
      if (text.size() > 100)
        text = text.substr(0, 97) + "...";
      std::cout << "    " << k.str() << " = " << text << "\n";
    }
  }
}

std::array<double, 21> parseConstants(const std::string& text) {
  std::array<double, 21> v{};
  std::stringstream ss(text);
  std::string item;
  std::size_t n = 0;
  while (std::getline(ss, item, ',')) {
    if (n >= 21)
      throw lamina::Error("expected exactly 21 comma-separated constants", {"--constants", 0, ""});
    char* end = nullptr;
    v[n] = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0')
      throw lamina::Error("constant " + std::to_string(n + 1) + " ('" + item + "') is not a number",
                          {"--constants", 0, ""});
    ++n;
  }
  if (n != 21)
    throw lamina::Error("expected exactly 21 comma-separated constants, got " + std::to_string(n),
                        {"--constants", 0, ""});
  return v;
}

/// The command line, parsed (every subcommand's options).
struct Args {
  lamina::core::SharedOptions shared; ///< --library, --catalog, --json
  std::string name;                   ///< NAME of show, add, layup, export, remove, drive
  std::string format = "json", from_catalog, constants;
  std::string path_name = "uniaxial-strain", out, kinematics = "finite";
  bool list_catalog = false, overwrite = false;
  double density = 0;
  std::vector<std::string> plies;
  mat::DriveOptions drive;
  std::string nonlinear_dispersion; ///< drive --nonlinear-dispersion FILE.csv
  int newton_iterations = 0;        ///< drive --newton-iterations (0: the law's default)
  double newton_tolerance = 0;      ///< drive --newton-tolerance (0: the law's default)

  /// @return the catalog file: --catalog, else the default
  std::filesystem::path catalogFile() const {
    return shared.catalog.empty() ? mat::Catalog::defaultPath()
                                  : std::filesystem::path(shared.catalog);
  }
};

/// The subcommands, to tell which one was given.
struct Commands {
  CLI::App *list, *show, *add, *layup, *export_card, *remove, *drive;
};

/// Declares `drive` and its options on @p app, into @p a.
CLI::App* addDriveCommand(CLI::App& app, Args& a) {
  auto* cmd = app.add_subcommand(
      "drive", "drive one material point along a strain path at a constant rate (CSV)");
  cmd->add_option("NAME", a.name, "library entry or catalog material")->required();
  cmd->add_option("--path", a.path_name, "strain path (one of the names listed)")
      ->check(CLI::IsMember(mat::kDrivePathNames.names()));
  cmd->add_option("--rate", a.drive.rate, "driven strain rate (1/s, 1e-12 to 1e12)")
      ->required() // range checked by checkRate (the same rule as homogenize)
      ->default_str("");
  cmd->add_option("--to", a.drive.to, "final driven strain (confined: compression, below 1)")
      ->required()
      ->check(CLI::PositiveNumber)
      ->default_str("");
  cmd->add_flag("--unload", a.drive.unload, "drive back to zero strain at the same rate");
  cmd->add_option("--steps", a.drive.steps, "time steps per leg")->check(CLI::Range(1, 100000000));
  cmd->add_option("--kinematics", a.kinematics, "finite (rotation-free frame, J = det F) | small")
      ->check(CLI::IsMember(mat::kKinematicsNames.names()));
  cmd->add_option("--out", a.out, "CSV file to write")->required();
  cmd->add_option("--nonlinear-dispersion", a.nonlinear_dispersion,
                  "reduced-order entries: CSV of D_nonlin (eq. 40, kg/m) along the history");
  cmd->add_option("--newton-iterations", a.newton_iterations,
                  "reduced-order entries: Newton cap per step (default 50)")
      ->check(CLI::Range(1, 10000))
      ->default_str("");
  cmd->add_option("--newton-tolerance", a.newton_tolerance,
                  "reduced-order entries: Newton tolerance, relative strain (default 1e-10)")
      ->check(CLI::Range(1e-16, 1e-2))
      ->default_str("");
  return cmd;
}

/// Declares every subcommand and option on @p app, into @p a.
Commands addCommands(CLI::App& app, Args& a) {
  lamina::core::showDefaults(app);
  Commands c{};
  c.list = app.add_subcommand("list", "list the library entries");
  c.list->add_flag("--catalog-entries", a.list_catalog,
                   "list the catalog's base materials instead");
  c.show = app.add_subcommand("show", "show one entry");
  c.show->add_option("NAME", a.name, "entry name")->required();
  c.add = app.add_subcommand("add", "add an entry from the catalog or from 21 constants");
  c.add->add_option("NAME", a.name, "new entry name")->required();
  auto* from = c.add->add_option("--from-catalog", a.from_catalog, "catalog key");
  auto* constants = c.add->add_option(
      "--constants", a.constants, "C11,C12,...,C66: upper triangle row by row, lamina order, Pa");
  c.add->add_option("--density", a.density, "kg/m^3 (required with --constants)")->default_str("");
  c.add->add_flag("--overwrite", a.overwrite, "replace an existing entry of that name");
  from->excludes(constants);
  c.layup = app.add_subcommand("layup", "store a layup of plies as a new entry");
  c.layup->add_option("NAME", a.name, "new entry name")->required();
  c.layup->add_option("--ply", a.plies, "MATERIAL:ANGLE_DEG:THICKNESS_M (repeat, bottom to top)")
      ->required()
      ->allow_extra_args(false); // one value per flag, so a positional may follow
  c.layup->add_flag("--overwrite", a.overwrite, "replace an existing entry of that name");
  c.export_card = app.add_subcommand("export", "print a card for another code");
  c.export_card->add_option("NAME", a.name, "entry name")->required();
  c.export_card->add_option("--format", a.format, "card format (one of the names listed)")
      ->check(CLI::IsMember(mat::kExportFormatNames.names()));
  c.remove = app.add_subcommand("remove", "remove an entry");
  c.remove->add_option("NAME", a.name, "entry name")->required();
  c.drive = addDriveCommand(app, a);
  // the library and the catalog are the program's two files: every
  // subcommand takes both (the catalog is read by list --catalog-entries,
  // add, layup and drive), so a script may name them once, first
  using lamina::core::Shared;
  const Shared files = Shared::Library | Shared::Catalog;
  lamina::core::addSharedOptions(app, a.shared,
                                 {{c.list, files | Shared::Json},
                                  {c.show, files | Shared::Json},
                                  {c.add, files},
                                  {c.layup, files},
                                  {c.export_card, files},
                                  {c.remove, files},
                                  {c.drive, files}});
  return c;
}

/// `list`: the library's entries, or the catalog's materials; text, or
/// one JSON array (--json).
void listEntries(const Args& a, const std::filesystem::path& library) {
  nlohmann::json out = nlohmann::json::array();
  if (a.list_catalog) {
    const mat::Catalog cat(a.catalogFile());
    for (const auto& n : cat.names()) {
      out.push_back({{"name", n}, {"description", cat.get(n).description}});
      if (!a.shared.json)
        std::cout << n << "  " << cat.get(n).description << "\n";
    }
  } else {
    const mat::Library lib(library);
    for (const auto& n : lib.names()) {
      const auto& m = lib.get(n);
      const std::string symmetry = mat::toString(mat::classify(m.C).cls);
      nlohmann::json entry{{"name", n}, {"kind", m.kind}, {"symmetry", symmetry}};
      std::string phases;
      for (const auto& p : m.phases) {
        entry["phases"].push_back({{"name", p.name}, {"law", mat::toString(p.law.kind)}});
        phases += (phases.empty() ? "" : ", ") + p.name + " (" + mat::toString(p.law.kind) + ")";
      }
      out.push_back(entry);
      if (!a.shared.json)
        std::cout << n << "  " << m.kind << "  " << symmetry
                  << (phases.empty() ? "" : "  phases " + phases) << "\n";
    }
  }
  if (a.shared.json)
    std::cout << out.dump(2) << "\n";
}

/// `add`: the new entry, from the catalog or from 21 constants.
mat::Material newEntry(const Args& a) {
  if (!a.from_catalog.empty())
    return mat::catalogEntry(mat::Catalog(a.catalogFile()), a.from_catalog, a.name,
                             "materials add");
  if (a.constants.empty())
    throw lamina::Error("give --from-catalog KEY or --constants C11,...,C66", {"add", 0, ""});
  if (!(a.density > 0))
    throw lamina::Error(a.density == 0 ? "--density (kg/m^3) is required with --constants"
                                       : "density must be > 0 (kg/m^3)",
                        {"--density", 0, ""});
  mat::Material m;
  m.C = mat::Stiffness::fromUpperTriangle(parseConstants(a.constants));
  m.density = a.density;
  m.kind = "constants";
  m.provenance.insert("input", a.constants);
  m.name = a.name;
  mat::stampProvenance(m, "materials add");
  return m;
}

/// `layup`: the plies stacked into a new entry of @p library.
void addLayup(const Args& a, const std::filesystem::path& library) {
  std::vector<mat::Ply> stack;
  for (const auto& p : a.plies)
    stack.push_back(mat::parsePly(p));
  mat::MaterialSource source(library.string(), a.shared.catalog);
  const mat::Material m = mat::layupEntry(a.name, stack, source, "materials layup");
  mat::Library(library).add(m, a.overwrite);
  std::cerr << "added layup '" << a.name << "' (" << stack.size() << " plies, "
            << lamina::core::formatShort(*m.thickness) << " m) to " << library.string() << "\n";
}

/// The Newton options of `drive` (the law's defaults where not given).
mat::ReducedOrderOptions newtonOptions(const Args& a) {
  mat::ReducedOrderOptions o;
  if (a.newton_iterations > 0)
    o.max_iterations = a.newton_iterations;
  if (a.newton_tolerance > 0)
    o.tolerance = a.newton_tolerance;
  return o;
}

/// Throws naming the option when a reduced-order option is given for @p law
/// of another kind.
void checkReducedOrderOptions(const Args& a, const mat::ConstitutiveLaw& law) {
  if (law.kind() == mat::LawKind::ReducedOrder)
    return;
  const std::pair<bool, const char*> given[] = {
      {!a.nonlinear_dispersion.empty(), "--nonlinear-dispersion"},
      {a.newton_iterations > 0, "--newton-iterations"},
      {a.newton_tolerance > 0, "--newton-tolerance"}};
  for (const auto& [set, option] : given)
    if (set)
      throw lamina::Error(std::string(option) + " applies to reduced-order entries; '" + a.name +
                              "' is a " + mat::toString(law.kind()) + " law",
                          {"", 0, option});
}

/// `drive`: the rate, the strain and the outputs checked before anything is
/// computed, then the point driven and its CSV (and, for a reduced-order
/// law, its D_nonlin CSV) written.
void driveEntry(Args a, const std::filesystem::path& library) {
  // both names were checked by CLI::IsMember against the same tables
  a.drive.path = *mat::kDrivePathNames.parse(a.path_name);
  a.drive.kinematics = *mat::kKinematicsNames.parse(a.kinematics);
  mat::checkRate(a.drive.rate, "--rate");
  mat::checkFinalStrain(a.drive.path, a.drive.to, "--to");
  // never over a device, a FIFO, a directory, nor over the library or the catalog
  lamina::core::checkOutput(a.out, {library, a.catalogFile()}, "--out");
  if (!a.nonlinear_dispersion.empty()) {
    lamina::core::checkOutput(a.nonlinear_dispersion, {library, a.catalogFile()},
                              "--nonlinear-dispersion");
    namespace fs = std::filesystem;
    if (fs::weakly_canonical(lamina::core::resolveLinks(a.nonlinear_dispersion)) ==
        fs::weakly_canonical(lamina::core::resolveLinks(a.out)))
      throw lamina::Error("names the same file as --out", {a.out, 0, "--nonlinear-dispersion"});
  }
  mat::MaterialSource source(library.string(), a.shared.catalog);
  const mat::LawPtr law = source.law(a.name, newtonOptions(a));
  checkReducedOrderOptions(a, *law);
  std::vector<mat::DispersionRow> dispersion;
  std::function<void(const mat::DriveStep&)> observer;
  if (!a.nonlinear_dispersion.empty())
    observer =
        mat::recordNonlinearDispersion(dynamic_cast<const mat::ReducedOrderLaw&>(*law), dispersion);
  const std::vector<mat::DriveRow> rows = mat::drive(*law, a.drive, observer);
  mat::writeDriveCsv(a.out, rows);
  if (!a.nonlinear_dispersion.empty())
    mat::writeDispersionCsv(a.nonlinear_dispersion, dispersion);
  std::cerr << "drove '" << a.name << "' (" << mat::toString(law->kind()) << ") along "
            << a.path_name << " at " << lamina::core::formatShort(a.drive.rate) << " /s to "
            << lamina::core::formatShort(a.drive.to) << ": " << rows.size() << " rows in " << a.out
            << (a.nonlinear_dispersion.empty() ? "" : ", D_nonlin in " + a.nonlinear_dispersion)
            << "\n";
}

/// What `show` adds on screen for a reduced-order entry: per phase its law,
/// density and partitions, and the state per point (reads the side file;
/// the JSON view is mat::showJson's).
void showReducedOrder(const mat::Library& lib, const mat::Material& m) {
  const mat::ReducedOrderLaw law(m.name, mat::readReducedOrderEntry(lib, m));
  const std::vector<int> count = law.model().partitionsPerPhase();
  std::cout << "  phases (law, density, partitions):\n";
  for (std::size_t p = 0; p < m.phases.size(); ++p) {
    const mat::ReducedOrderPhase& ph = m.phases[p];
    std::cout << "    " << ph.name << "  " << mat::toString(ph.law.kind) << " ("
              << mat::toString(mat::classify(ph.law.C).cls) << " at J = 1)  "
              << lamina::core::formatShort(ph.density, 6) << " kg/m^3  " << count[p]
              << (count[p] == 1 ? " partition" : " partitions") << "\n";
  }
  const bool clustering = law.model().scheme == mat::ReducedOrderScheme::Clustering;
  std::cout << "  scheme " << mat::toString(law.model().scheme)
            << (clustering ? " (clustering analysis)" : " (transformation-field analysis)") << "\n"
            << "  partitions " << law.model().partitions() << ", "
            << law.nonlinearPartitions().size()
            << " nonlinear (the Newton unknowns: " << 6 * law.unknownPartitions().size()
            << " per point)\n"
            << "  state " << law.stateSize()
            << " doubles per point (per partition: its strain, 6, then its law's state"
            << (clustering && law.stateSize() > 0 ? "; then the reference shear modulus, 1" : "")
            << ")\n";
}

/// `show`: one entry, human-readable or as JSON.
void showEntry(const Args& a, const std::filesystem::path& path) {
  const mat::Library lib(path);
  const mat::Material& m = lib.get(a.name);
  if (a.shared.json) {
    std::cout << mat::showJson(lib, m).dump(2) << "\n";
    return;
  }
  printHuman(m);
  if (m.kind == mat::kReducedOrderKind)
    showReducedOrder(lib, m);
}

/// Runs the subcommand of @p c that was given.
void runCommand(const Commands& c, const Args& a) {
  const auto path = mat::Library::resolvePath(a.shared.library);
  if (c.list->parsed()) {
    listEntries(a, path);
  } else if (c.show->parsed()) {
    showEntry(a, path);
  } else if (c.add->parsed()) {
    mat::Library(path).add(newEntry(a), a.overwrite);
    std::cerr << "added '" << a.name << "' to " << path.string() << "\n";
  } else if (c.layup->parsed()) {
    addLayup(a, path);
  } else if (c.export_card->parsed()) {
    const mat::Library lib(path);
    std::cout << mat::exportCard(lib.get(a.name), mat::parseExportFormat(a.format));
  } else if (c.drive->parsed()) {
    driveEntry(a, path);
  } else if (c.remove->parsed()) {
    mat::Library(path).remove(a.name);
    std::cerr << "removed '" << a.name << "' from " << path.string() << "\n";
  }
}

} // namespace

namespace lamina::materials {

int runProgram(int argc, char** argv, UnexpectedErrors unexpected) {
  CLI::App app{"lamina materials library: list, show, add, layup, export, remove, drive.\n"
               "Stiffness in Pa, lamina order [xx, yy, zz, xy, yz, xz], engineering shear."};
  Args args;
  const Commands commands = addCommands(app, args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return lamina::core::reportUsageError(app, e, "materials");
  }
  try {
    runCommand(commands, args);
  } catch (const lamina::Error& e) {
    std::cerr << "materials: error: " << e.what() << "\n";
    return lamina::kExitUserError;
  } catch (const std::exception& e) {
    if (unexpected == UnexpectedErrors::Rethrow)
      throw;
    std::cerr << "materials: error: " << e.what() << "\n";
    return lamina::kExitUserError;
  } catch (...) {
    if (unexpected == UnexpectedErrors::Rethrow)
      throw;
    std::cerr << "materials: error: unexpected error (not a std::exception)\n";
    return lamina::kExitUserError;
  }
  return 0;
}

} // namespace lamina::materials
