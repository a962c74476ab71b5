// The library file: exact round trips (17 significant digits give back the
// same doubles), provenance kept verbatim, atomic replacement that leaves a
// pre-existing file untouched when an add fails, refusal of files that are
// not lamina libraries, remove.

#include "core/error.hpp"
#include "materials/library.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

namespace mat = lamina::materials;
using lamina::test::errorOf;
using lamina::test::readFile;
using lamina::test::TempDir;
using lamina::test::writeFile;

namespace {

// A random SPD stiffness whose entries use the full 53-bit mantissa and span
// several decades (so that 17 digits are needed to round-trip them).
mat::Matrix6 randomFullPrecisionSpd(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(6.0, 12.0);
  mat::Matrix6 a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      a(i, j) = u(rng) * std::pow(10.0, e(rng) / 2);
  mat::Matrix6 c = a * a.transpose() + 1e6 * mat::Matrix6::Identity();
  return 0.5 * (c + c.transpose());
}

mat::Material randomMaterial(std::mt19937_64& rng, const std::string& name) {
  std::uniform_real_distribution<double> rho(1.0, 20000.0);
  mat::Material m;
  m.name = name;
  m.C = mat::Stiffness(randomFullPrecisionSpd(rng));
  m.density = rho(rng) / 3.0; // a non-terminating decimal
  m.kind = "homogenized";
  return m;
}

bool hasTempLeftovers(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos)
      return true;
  return false;
}

} // namespace

// %.17g text parses back to the same double (IEEE 754: 17 significant digits
// suffice for binary64), so C and density must come back bit-identical,
// through the file and a fresh Library object.
TEST(Library, WriteThenReadIsBitIdentical) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  std::mt19937_64 rng(42);
  std::vector<mat::Material> written;
  {
    mat::Library lib(path);
    for (int k = 0; k < 8; ++k) {
      written.push_back(randomMaterial(rng, "m" + std::to_string(k)));
      lib.add(written.back());
    }
  }
  const mat::Library back(path);
  ASSERT_EQ(back.names().size(), written.size());
  for (const mat::Material& w : written) {
    const mat::Material& r = back.get(w.name);
    EXPECT_EQ(r.C.matrix(), w.C.matrix()) << w.name;
    EXPECT_EQ(r.density, w.density) << w.name;
    EXPECT_EQ(r.kind, w.kind);
  }
}

// Names that need quoting in TOML (dots, '+') survive. (Names with
// spaces, quotes or '/' are refused: malformed_library_test.)
TEST(Library, AwkwardNamesRoundTrip) {
  TempDir dir;
  std::mt19937_64 rng(1);
  const std::vector<std::string> names{"carbon-epoxy-0.6mm", "a.b.c", "T300+epoxy", "ply-1_x"};
  {
    mat::Library lib(dir / "lib.toml");
    for (const auto& n : names)
      lib.add(randomMaterial(rng, n));
  }
  const mat::Library back(dir / "lib.toml");
  for (const auto& n : names)
    EXPECT_TRUE(back.contains(n)) << n;
}

// Layup fields and provenance of every TOML type come back as written.
TEST(Library, ProvenanceAndLayupFieldsSurvive) {
  TempDir dir;
  std::mt19937_64 rng(9);
  mat::Material m = randomMaterial(rng, "stack");
  m.kind = "layup";
  m.thickness = 1.2345678901234567e-3;
  m.plies = {{"ply-a", 0.0, 6e-4}, {"ply.b", -45.0, 6.1234567890123456e-4}};
  m.side_file = "fields/stack.h5";
  m.provenance.insert("input", "[cell]\nresolution = 32\npath = 'C:\\\\x'\n\"quoted\"\n");
  m.provenance.insert("solver", "cg \"Krylov\" \\ backslash, tab\there");
  m.provenance.insert("resolution", 32);
  m.provenance.insert("tolerance", 1e-8);
  m.provenance.insert("residual", 3.3333333333333335e-9);
  m.provenance.insert("converged", true);
  m.provenance.insert("sizes", toml::array{1, 2.5, "three"});
  m.provenance.insert("nested", toml::table{{"a", 1}, {"b c", "d"}});
  m.provenance.insert("unicode", "tau = \xcf\x84, 5 \xc2\xb0");
  {
    mat::Library lib(dir / "lib.toml");
    lib.add(m);
  }
  const mat::Library back(dir / "lib.toml");
  const mat::Material& r = back.get("stack");
  EXPECT_EQ(r.kind, "layup");
  ASSERT_TRUE(r.thickness.has_value());
  EXPECT_EQ(*r.thickness, *m.thickness);
  ASSERT_EQ(r.plies.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.plies[i].material, m.plies[i].material);
    EXPECT_EQ(r.plies[i].angle_deg, m.plies[i].angle_deg);
    EXPECT_EQ(r.plies[i].thickness, m.plies[i].thickness);
  }
  EXPECT_EQ(r.side_file, m.side_file);
  EXPECT_TRUE(r.provenance == m.provenance) << "written:\n"
                                            << m.provenance << "\nread:\n"
                                            << r.provenance;
}

// A failing add (duplicate name, invalid stiffness, bad density) changes
// nothing: the file is byte-identical and no temporary file is left behind.
TEST(Library, FailedAddLeavesFileUntouched) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  std::mt19937_64 rng(3);
  mat::Library lib(path);
  lib.add(randomMaterial(rng, "first"));
  lib.add(randomMaterial(rng, "second"));
  const std::string before = readFile(path);

  EXPECT_THROW(lib.add(randomMaterial(rng, "first")), lamina::Error);
  EXPECT_EQ(readFile(path), before);

  mat::Material bad = randomMaterial(rng, "indefinite");
  mat::Matrix6 c = bad.C.matrix();
  c(0, 0) = -c(0, 0);
  bad.C = mat::Stiffness(c);
  const std::string msg = errorOf([&] { lib.add(bad); });
  EXPECT_NE(msg.find("indefinite"), std::string::npos) << msg;
  EXPECT_EQ(readFile(path), before);

  mat::Material light = randomMaterial(rng, "no-mass");
  light.density = -1;
  EXPECT_THROW(lib.add(light), lamina::Error);
  light.density = std::nan("");
  EXPECT_THROW(lib.add(light), lamina::Error);
  EXPECT_EQ(readFile(path), before);
  EXPECT_FALSE(hasTempLeftovers(dir.path()));
  EXPECT_EQ(mat::Library(path).names(), (std::vector<std::string>{"first", "second"}));
}

// Overwrite replaces an entry when asked to.
TEST(Library, OverwriteReplacesEntry) {
  TempDir dir;
  std::mt19937_64 rng(4);
  mat::Library lib(dir / "lib.toml");
  lib.add(randomMaterial(rng, "x"));
  const mat::Material y = randomMaterial(rng, "x");
  lib.add(y, true);
  EXPECT_EQ(mat::Library(dir / "lib.toml").get("x").C.matrix(), y.C.matrix());
}

// A file without our [lamina] header is refused and left alone; the message
// names the path.
TEST(Library, RefusesFileThatIsNotOurs) {
  TempDir dir;
  const auto path = dir / "other.toml";
  const std::string foreign = "[tool.poetry]\nname = \"x\"\n";
  writeFile(path, foreign);
  const std::string msg = errorOf([&] { mat::Library lib(path); });
  EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("not a lamina materials library"), std::string::npos) << msg;
  EXPECT_EQ(readFile(path), foreign);
}

TEST(Library, RefusesWrongFormatStringAndVersion) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  writeFile(path, "[lamina]\nformat = \"someone-elses-library\"\nversion = 1\n");
  std::string msg = errorOf([&] { mat::Library lib(path); });
  EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("lamina.format"), std::string::npos) << msg;
  writeFile(path, "[lamina]\nformat = \"lamina-materials-library\"\nversion = 99\n");
  msg = errorOf([&] { mat::Library lib(path); });
  EXPECT_NE(msg.find("version"), std::string::npos) << msg;
}

// A missing file is an empty library; the first add creates it.
TEST(Library, MissingFileIsEmptyAndFirstAddCreatesIt) {
  TempDir dir;
  const auto path = dir / "sub" / "lib.toml";
  mat::Library lib(path);
  EXPECT_TRUE(lib.names().empty());
  std::mt19937_64 rng(5);
  lib.add(randomMaterial(rng, "a"));
  EXPECT_TRUE(std::filesystem::exists(path));
  EXPECT_TRUE(mat::Library(path).contains("a"));
}

// remove drops exactly one entry; an unknown name is an error that lists what
// the library holds, and the file is unchanged.
TEST(Library, RemoveWorksAndUnknownNameListsEntries) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  std::mt19937_64 rng(6);
  mat::Library lib(path);
  for (const char* n : {"alpha", "beta", "gamma"})
    lib.add(randomMaterial(rng, n));
  lib.remove("beta");
  EXPECT_EQ(mat::Library(path).names(), (std::vector<std::string>{"alpha", "gamma"}));
  const std::string before = readFile(path);
  const std::string msg = errorOf([&] { lib.remove("delta"); });
  EXPECT_NE(msg.find("delta"), std::string::npos) << msg;
  EXPECT_NE(msg.find("alpha, gamma"), std::string::npos) << msg;
  EXPECT_EQ(readFile(path), before);
}

// resolvePath: --library first, then $LAMINA_LIBRARY, then XDG/HOME.
TEST(Library, ResolvePathPrecedence) {
  ::setenv("LAMINA_LIBRARY", "/tmp/from-env.toml", 1);
  EXPECT_EQ(mat::Library::resolvePath("/tmp/cli.toml"), "/tmp/cli.toml");
  EXPECT_EQ(mat::Library::resolvePath(""), "/tmp/from-env.toml");
  ::unsetenv("LAMINA_LIBRARY");
  ::setenv("XDG_DATA_HOME", "/tmp/xdg", 1);
  EXPECT_EQ(mat::Library::resolvePath(""), "/tmp/xdg/lamina/library.toml");
  ::unsetenv("XDG_DATA_HOME");
}

// Micro-inertia fields: a dispersion zeta^2 D (a random Gram
// matrix, full precision, kg/m) and the cell size come back bit-identical.
TEST(Library, DispersionAndCellSizeRoundTrip) {
  TempDir dir;
  std::mt19937_64 rng(12);
  mat::Material m = randomMaterial(rng, "laminate");
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  mat::Matrix6 a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      a(i, j) = u(rng) * 1e-2 / 3.0;
  m.dispersion = a * a.transpose();
  m.cell_size = Eigen::Vector3d(2e-3 / 3, 1e-4, 7e-5);
  mat::Library(dir / "lib.toml").add(m);
  const mat::Material back = mat::Library(dir / "lib.toml").get("laminate");
  ASSERT_TRUE(back.dispersion && back.cell_size);
  EXPECT_EQ(*back.dispersion, *m.dispersion);
  EXPECT_EQ(*back.cell_size, *m.cell_size);
  // an entry without them stays without
  mat::Library(dir / "lib.toml").add(randomMaterial(rng, "plain"));
  EXPECT_FALSE(mat::Library(dir / "lib.toml").get("plain").dispersion);
}
