/// @file cli.cpp
/// @brief The `materials` program: list, show, add, layup, export, remove, drive.

#include "materials/cli.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "materials/catalog.hpp"
#include "materials/export.hpp"
#include "materials/layup.hpp"
#include "materials/library.hpp"
#include "materials/material_source.hpp"
#include "materials/point_driver.hpp"
#include "materials/symmetry.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <ctime>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace mat = lamina::materials;

namespace {

/// @return the --format names of mat::exportFormats(), for CLI::IsMember
std::vector<std::string> formatNames() {
  std::vector<std::string> names;
  for (const auto& f : mat::exportFormats())
    names.emplace_back(f.first);
  return names;
}

std::string nowIso() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

void printHuman(const mat::Material& m) {
  const mat::Symmetry s = mat::classify(m.C);
  const mat::EngineeringConstants e = m.C.engineering();
  auto g = [](double x) { return lamina::core::formatShort(x, 6); };
  std::cout << m.name << "  (" << m.kind << ")\n"
            << "  density   " << g(m.density) << " kg/m^3\n";
  if (m.thickness)
    std::cout << "  thickness " << g(*m.thickness) << " m\n";
  std::cout << "  symmetry  " << mat::toString(s.cls)
            << (s.axis >= 0 ? std::string(" (axis ") + "xyz"[s.axis] + ")" : "")
            << ", anisotropy index A^U = " << g(mat::anisotropyIndex(m.C)) << "\n"
            << "  C (GPa, lamina order xx yy zz xy yz xz):\n";
  for (int i = 0; i < 6; ++i) {
    std::cout << "   ";
    for (int j = 0; j < 6; ++j) {
      char buf[32];
      std::snprintf(buf, sizeof buf, " %11.5g", m.C(i, j) / 1e9);
      std::cout << buf;
    }
    std::cout << "\n";
  }
  std::cout << "  E1 " << g(e.E1) << "  E2 " << g(e.E2) << "  E3 " << g(e.E3) << " Pa\n"
            << "  G12 " << g(e.G12) << "  G23 " << g(e.G23) << "  G13 " << g(e.G13) << " Pa\n"
            << "  nu12 " << g(e.nu12) << "  nu13 " << g(e.nu13) << "  nu23 " << g(e.nu23) << "\n";
  if (m.cell_size)
    std::cout << "  cell size " << g((*m.cell_size)[0]) << " x " << g((*m.cell_size)[1]) << " x "
              << g((*m.cell_size)[2]) << " m\n";
  if (m.dispersion) {
    std::cout << "  dispersion zeta^2 D (kg/m, lamina order; micro-inertia, eq. 35):\n";
    for (int i = 0; i < 6; ++i) {
      std::cout << "   ";
      for (int j = 0; j < 6; ++j) {
        char buf[32];
        std::snprintf(buf, sizeof buf, " %11.4g", (*m.dispersion)(i, j));
        std::cout << buf;
      }
      std::cout << "\n";
    }
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
  if (!m.provenance.empty()) {
    std::cout << "  provenance:\n";
    for (const auto& [k, v] : m.provenance) {
      std::ostringstream os;
      v.visit([&os](const auto& x) { os << x; });
      std::string text = os.str();
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

} // namespace

namespace lamina::materials {

int runProgram(int argc, char** argv, UnexpectedErrors unexpected) {
  CLI::App app{"lamina materials library: list, show, add, layup, export, remove.\n"
               "Stiffness in Pa, lamina order [xx, yy, zz, xy, yz, xz], engineering shear."};
  app.require_subcommand(1);
  std::string libraryPath, catalogPath;
  app.add_option(
      "--library", libraryPath,
      "library file (default: $LAMINA_LIBRARY, else ~/.local/share/lamina/library.toml)");
  app.add_option("--catalog", catalogPath, "catalog file (default: the source tree's)");

  auto* list = app.add_subcommand("list", "list the library entries");
  bool listCatalog = false;
  list->add_flag("--catalog-entries", listCatalog, "list the catalog's base materials instead");

  std::string name, format = "json", fromCatalog, constants;
  bool json = false, overwrite = false;
  double density = 0;
  std::vector<std::string> plies;

  auto* show = app.add_subcommand("show", "show one entry");
  show->add_option("NAME", name, "entry name")->required();
  show->add_flag("--json", json, "print one JSON object");

  auto* add = app.add_subcommand("add", "add an entry from the catalog or from 21 constants");
  add->add_option("NAME", name, "new entry name")->required();
  auto* fromOpt = add->add_option("--from-catalog", fromCatalog, "catalog key");
  auto* constOpt = add->add_option("--constants", constants,
                                   "C11,C12,...,C66: upper triangle row by row, lamina order, Pa");
  add->add_option("--density", density, "kg/m^3 (required with --constants)");
  add->add_flag("--overwrite", overwrite, "replace an existing entry of that name");
  fromOpt->excludes(constOpt);

  auto* layup = app.add_subcommand("layup", "store a layup of plies as a new entry");
  layup->add_option("NAME", name, "new entry name")->required();
  layup->add_option("--ply", plies, "MATERIAL:ANGLE_DEG:THICKNESS_M (repeat, bottom to top)")
      ->required()
      ->allow_extra_args(false); // one value per flag, so a positional may follow
  layup->add_flag("--overwrite", overwrite, "replace an existing entry of that name");

  auto* exportCmd = app.add_subcommand("export", "print a card for another code");
  exportCmd->add_option("NAME", name, "entry name")->required();
  exportCmd->add_option("--format", format, "abaqus | calculix | lsdyna | lsdyna-small | json")
      ->check(CLI::IsMember(formatNames()));

  auto* remove = app.add_subcommand("remove", "remove an entry");
  remove->add_option("NAME", name, "entry name")->required();

  auto* driveCmd = app.add_subcommand(
      "drive", "drive one material point along a strain path at a constant rate (CSV)");
  std::string pathName = "uniaxial-strain", out, kinematics = "finite";
  mat::DriveOptions drive;
  driveCmd->add_option("NAME", name, "library entry or catalog material")->required();
  driveCmd->add_option("--path", pathName, "uniaxial-stress | uniaxial-strain | shear | confined")
      ->check(CLI::IsMember(mat::drivePathNames()));
  driveCmd->add_option("--rate", drive.rate, "driven strain rate (1/s, 1e-12 to 1e12; required)")
      ->required(); // range checked by checkRate (the same rule as homogenize)
  driveCmd
      ->add_option("--to", drive.to,
                   "final driven strain (required; confined: compression, below 1)")
      ->required()
      ->check(CLI::PositiveNumber);
  driveCmd->add_flag("--unload", drive.unload, "drive back to zero strain at the same rate");
  driveCmd->add_option("--steps", drive.steps, "time steps per leg (default 200)")
      ->check(CLI::Range(1, 100000000));
  driveCmd
      ->add_option("--kinematics", kinematics,
                   "finite (rotation-free frame, J = det F; default) | small")
      ->check(CLI::IsMember({"finite", "small"}));
  driveCmd->add_option("--out", out, "CSV file to write")->required();
  driveCmd->add_option("--library", libraryPath, "library file (as before the subcommand)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) // --help: CLI11 prints the help text
      return app.exit(e);
    // One line on stderr (CLI11's default adds a second "Run with --help" line).
    std::cerr << "materials: error: " << e.what() << " (see --help)\n";
    return lamina::kExitUsage;
  }

  try {
    const auto path = mat::Library::resolvePath(libraryPath);
    auto catalog = [&] {
      return mat::Catalog(catalogPath.empty() ? mat::Catalog::defaultPath()
                                              : std::filesystem::path(catalogPath));
    };
    if (list->parsed()) {
      if (listCatalog) {
        const mat::Catalog cat = catalog();
        for (const auto& n : cat.names())
          std::cout << n << "  " << cat.get(n).description << "\n";
        return 0;
      }
      const mat::Library lib(path);
      for (const auto& n : lib.names()) {
        const auto& m = lib.get(n);
        std::cout << n << "  " << m.kind << "  " << mat::toString(mat::classify(m.C).cls) << "\n";
      }
      return 0;
    }
    if (show->parsed()) {
      const mat::Library lib(path);
      const auto& m = lib.get(name);
      if (json)
        std::cout << mat::materialToJson(m).dump(2) << "\n";
      else
        printHuman(m);
      return 0;
    }
    if (add->parsed()) {
      mat::Material m;
      if (!fromCatalog.empty()) {
        m = catalog().get(fromCatalog).toMaterial();
        m.provenance.insert("catalog_key", fromCatalog);
      } else if (!constants.empty()) {
        if (!(density > 0))
          throw lamina::Error(density == 0 ? "--density (kg/m^3) is required with --constants"
                                           : "density must be > 0 (kg/m^3)",
                              {"--density", 0, ""});
        m.C = mat::Stiffness::fromUpperTriangle(parseConstants(constants));
        m.density = density;
        m.kind = "constants";
        m.provenance.insert("input", constants);
      } else {
        throw lamina::Error("give --from-catalog KEY or --constants C11,...,C66", {"add", 0, ""});
      }
      m.name = name;
      m.provenance.insert("tool", "materials add");
      m.provenance.insert("version", LAMINA_VERSION);
      m.provenance.insert("time", nowIso());
      mat::Library lib(path);
      lib.add(m, overwrite);
      std::cerr << "added '" << name << "' to " << path.string() << "\n";
      return 0;
    }
    if (layup->parsed()) {
      std::vector<mat::Ply> stack;
      for (const auto& p : plies)
        stack.push_back(mat::parsePly(p));
      mat::MaterialSource source(path.string(), catalogPath);
      mat::Material m =
          mat::makeLayup(name, stack, [&](const std::string& n) { return source.get(n); });
      m.provenance.insert("tool", "materials layup");
      m.provenance.insert("version", LAMINA_VERSION);
      m.provenance.insert("time", nowIso());
      mat::Library lib(path);
      lib.add(m, overwrite);
      std::cerr << "added layup '" << name << "' (" << stack.size() << " plies, "
                << lamina::core::formatShort(*m.thickness) << " m) to " << path.string() << "\n";
      return 0;
    }
    if (exportCmd->parsed()) {
      const mat::Library lib(path);
      std::cout << mat::exportCard(lib.get(name), mat::parseExportFormat(format));
      return 0;
    }
    if (driveCmd->parsed()) {
      drive.path = *mat::parseDrivePath(pathName);
      drive.kinematics = kinematics == "small" ? mat::Kinematics::Small : mat::Kinematics::Finite;
      mat::checkRate(drive.rate, "--rate");
      mat::checkFinalStrain(drive.path, drive.to, "--to");
      // before anything is computed: never over a device, a FIFO, a
      // directory, nor over the library or the catalog
      lamina::core::checkOutput(out,
                                {path, catalogPath.empty() ? mat::Catalog::defaultPath()
                                                           : std::filesystem::path(catalogPath)},
                                "--out");
      mat::MaterialSource source(path.string(), catalogPath);
      const mat::LawPtr law = source.law(name);
      const std::vector<mat::DriveRow> rows = mat::drive(*law, drive);
      mat::writeDriveCsv(out, rows);
      std::cerr << "drove '" << name << "' (" << mat::toString(law->kind()) << ") along "
                << pathName << " at " << drive.rate << " /s to " << drive.to << ": " << rows.size()
                << " rows in " << out << "\n";
      return 0;
    }
    if (remove->parsed()) {
      mat::Library lib(path);
      lib.remove(name);
      std::cerr << "removed '" << name << "' from " << path.string() << "\n";
      return 0;
    }
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
