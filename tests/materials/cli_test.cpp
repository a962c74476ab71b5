// The `materials` program end to end, with a temporary library: Table 1 of
// the membrane paper through `add` + `show --json`, 21 constants in the
// documented order, a [0/90] layup equal to the hand average, export cards
// in the manuals' field orders; concurrent writers (two processes, two
// shells) whose entries all land in the file, and a writer killed mid-way
// that leaves a readable library.

#include "core/format.hpp"
#include "materials/conversions.hpp"
#include "materials/library.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

namespace mat = lamina::materials;
using lamina::test::runMaterials;
using lamina::test::TempDir;

namespace {

constexpr double GPa = 1e9;

mat::Matrix6 table1() {
  return lamina::test::membranePaperTable1();
}

mat::Matrix6 jsonMatrix(const nlohmann::json& j) {
  mat::Matrix6 c;
  EXPECT_EQ(j.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(j.at(i).size(), 6u);
    for (int k = 0; k < 6; ++k)
      c(i, k) = j.at(i).at(k).get<double>();
  }
  return c;
}

// The numbers of the card lines between the line starting with @p start and
// the next keyword line ('*').
std::vector<double> cardNumbers(const std::string& card, const std::string& start) {
  std::vector<double> out;
  std::istringstream in(card);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind(start, 0) == 0) {
      inside = true;
      continue;
    }
    if (!inside || line.empty() || line.rfind("**", 0) == 0)
      continue;
    if (line[0] == '*')
      break;
    std::istringstream items(line);
    std::string item;
    while (std::getline(items, item, ','))
      out.push_back(std::stod(item));
  }
  return out;
}

class MaterialsProgram : public ::testing::Test {
protected:
  lamina::test::RunResult run(const std::string& args) { return runMaterials(dir_, lib_, args); }
  nlohmann::json showJson(const std::string& name) {
    const auto r = run("show '" + name + "' --json");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }
  TempDir dir_;
  std::filesystem::path lib_ = dir_ / "library.toml";
};

} // namespace

// The materials-library interface: `materials show` of the Table 1 material in --json
// reproduces the table (c11 = 150, c12 = 40, c13 = 10, c22 = 150, c23 = 80,
// c33 = 150, c44 = 80, c55 = 20, c66 = 30 GPa, zeros elsewhere) exactly.
TEST_F(MaterialsProgram, Table1ShowJsonReproducesTheTable) {
  const auto r = run("add t1 --from-catalog table1-anisotropic");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = showJson("t1");
  EXPECT_EQ(j.at("name"), "t1");
  EXPECT_EQ(jsonMatrix(j.at("C")), table1());
  EXPECT_EQ(j.at("kind"), "catalog");
  EXPECT_EQ(j.at("symmetry"), "orthotropic");
  EXPECT_GT(j.at("density").get<double>(), 0);
  // G12 = c44, G23 = c55, G13 = c66 for this block-diagonal tensor (1e-15:
  // inverse of an inverse).
  EXPECT_NEAR(j.at("engineering").at("G23").get<double>(), 20 * GPa, 1e-15 * 20 * GPa);
  EXPECT_EQ(j.at("provenance").at("catalog_key"), "table1-anisotropic");
}

// The micro-inertia interface: `show --json` of an entry with micro-inertia has
// "dispersion" (6x6, kg/m, as stored, bit for bit) and "cell_size" (m), and
// the human form prints the characteristic lengths sqrt(zeta^2 D_II / rho).
// A [0/90] layup of it averages the plies' dispersions rotated like C: the
// 90-degree ply swaps xx and yy, so the layup's D_xx = D_yy = (D_xx + D_yy)/2
// of the ply (exact: two equal weights 1/2 of exactly representable values).
TEST_F(MaterialsProgram, DispersionIsShownAndAveragedInLayups) {
  lamina::test::writeFile(lib_,
                          "[lamina]\nformat = \"lamina-materials-library\"\nversion = 1\n"
                          "[materials.lam]\nkind = \"homogenized\"\ndensity = 3125.0\n"
                          "cell_size = [0.002, 0.0001, 0.0001]\n"
                          "C = [[6e9, 5e9, 5e9, 0, 0, 0], [5e9, 74e9, 24e9, 0, 0, 0],\n"
                          "     [5e9, 24e9, 74e9, 0, 0, 0], [0, 0, 0, 7e7, 0, 0],\n"
                          "     [0, 0, 0, 0, 25e9, 0], [0, 0, 0, 0, 0, 7e7]]\n"
                          "dispersion = [[5e-4, 5e-5, 5e-5, 0, 0, 0], [5e-5, 2.5e-5, 0, 0, 0, 0],\n"
                          "     [5e-5, 0, 2.5e-5, 0, 0, 0], [0, 0, 0, 6e-4, 0, 0],\n"
                          "     [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 6e-4]]\n");
  const nlohmann::json j = showJson("lam");
  const auto D = jsonMatrix(j.at("dispersion"));
  EXPECT_EQ(D(0, 0), 5e-4);
  EXPECT_EQ(D(0, 1), 5e-5);
  EXPECT_EQ(D(3, 3), 6e-4);
  EXPECT_EQ(j.at("cell_size").get<std::vector<double>>(), (std::vector<double>{2e-3, 1e-4, 1e-4}));
  const auto human = run("show lam");
  ASSERT_EQ(human.status, 0) << human.err;
  char xx[64];
  std::snprintf(xx, sizeof xx, "xx %s",
                lamina::core::formatShort(std::sqrt(5e-4 / 3125.0)).c_str());
  EXPECT_NE(human.out.find(xx), std::string::npos) << human.out;
  ASSERT_EQ(run("layup lam-0-90 --ply lam:0:1e-3 --ply lam:90:1e-3").status, 0);
  const auto L = jsonMatrix(showJson("lam-0-90").at("dispersion"));
  EXPECT_EQ(L(0, 0), 0.5 * (5e-4 + 2.5e-5));
  EXPECT_EQ(L(1, 1), 0.5 * (5e-4 + 2.5e-5));
  EXPECT_EQ(L(3, 3), 6e-4); // xy shear: rotating by 90 degrees maps it to itself
}

// `add --constants` takes the upper triangle row by row in lamina order;
// written with 17 digits they come back bit-identical from `show --json`.
TEST_F(MaterialsProgram, AddConstantsRoundTripsInDocumentedOrder) {
  std::mt19937_64 rng(99);
  const mat::Stiffness c(lamina::test::randomSpd(rng));
  std::string text;
  for (double v : c.upperTriangle())
    text += (text.empty() ? "" : ",") + lamina::core::formatExact(v);
  const double rho = 1234.5678901234567;
  const auto r =
      run("add rnd --constants " + text + " --density " + lamina::core::formatExact(rho));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = showJson("rnd");
  const mat::Matrix6 back = jsonMatrix(j.at("C"));
  EXPECT_EQ(back, c.matrix());
  EXPECT_EQ(back(0, 5), c.upperTriangle()[5]); // constant #6 is C16
  EXPECT_EQ(back(1, 1), c.upperTriangle()[6]); // constant #7 is C22
  EXPECT_EQ(j.at("density").get<double>(), rho);
  EXPECT_EQ(j.at("kind"), "constants");
  EXPECT_EQ(j.at("symmetry"), "triclinic");
  // And through the library API, from the file itself.
  EXPECT_EQ(mat::Library(lib_).get("rnd").C.matrix(), c.matrix());
}

// Layups: a [0/90] layup of Table 1 gives the exact averaged D:
// C11 = C22 = 150, C13 = C23 = (10 + 80)/2, C55 = C66 = (20 + 30)/2,
// C44 = 80 GPa. Thicknesses 2^-10 m make every operation exact.
TEST_F(MaterialsProgram, LayupZeroNinetyEqualsHandAverage) {
  ASSERT_EQ(run("add t1 --from-catalog table1-anisotropic").status, 0);
  const auto r = run("layup cross --ply t1:0:0.0009765625 --ply t1:90:0.0009765625");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = showJson("cross");
  const mat::Matrix6 c = jsonMatrix(j.at("C"));
  EXPECT_EQ(c(0, 0), 150 * GPa);
  EXPECT_EQ(c(1, 1), 150 * GPa);
  EXPECT_EQ(c(2, 2), 150 * GPa);
  EXPECT_EQ(c(0, 1), 40 * GPa);
  EXPECT_EQ(c(0, 2), 45 * GPa);
  EXPECT_EQ(c(1, 2), 45 * GPa);
  EXPECT_EQ(c(3, 3), 80 * GPa);
  EXPECT_EQ(c(4, 4), 25 * GPa);
  EXPECT_EQ(c(5, 5), 25 * GPa);
  EXPECT_EQ(c(3, 4), 0.0);
  EXPECT_EQ(c(0, 3), 0.0);
  EXPECT_EQ(j.at("thickness").get<double>(), 0.001953125);
  EXPECT_EQ(j.at("density"), showJson("t1").at("density"));
  EXPECT_EQ(j.at("kind"), "layup");
  EXPECT_EQ(j.at("plies").size(), 2u);
  // A ply may also name a catalog key directly.
  ASSERT_EQ(run("layup direct --ply table1-anisotropic:0:0.0009765625 "
                "--ply table1-anisotropic:90:0.0009765625")
                .status,
            0);
  EXPECT_EQ(jsonMatrix(showJson("direct").at("C")), c);
}

// Abaqus *ELASTIC, TYPE=ANISOTROPIC lists D1111 D1122 D2222 D1133 D2233
// D3333 D1112 D2212 D3312 D1212 D1113 D2213 D3313 D1213 D1313 D1123 D2223
// D3323 D1223 D1323 D2323: for Table 1, #10 D1212 = xy = 80, #15 D1313 =
// xz = 30, #21 D2323 = yz = 20 GPa.
TEST_F(MaterialsProgram, AbaqusAndCalculixCardsFollowManualOrder) {
  ASSERT_EQ(run("add t1 --from-catalog table1-anisotropic").status, 0);
  for (const auto& [format, keyword] :
       {std::pair<std::string, std::string>{"abaqus", "*ELASTIC, TYPE=ANISOTROPIC"},
        {"calculix", "*ELASTIC, TYPE=ANISO"}}) {
    const auto r = run("export t1 --format " + format);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<double> v = cardNumbers(r.out, keyword);
    ASSERT_EQ(v.size(), 21u) << r.out;
    const double expected[21] = {150, 40, 150, 10, 80, 150, 0, 0, 0, 80, 0,
                                 0,   0,  0,   30, 0,  0,   0, 0, 0, 20};
    for (int k = 0; k < 21; ++k)
      EXPECT_EQ(v[static_cast<std::size_t>(k)], expected[k] * GPa) << format << " value #" << k + 1;
    const std::vector<double> rho = cardNumbers(r.out, "*DENSITY");
    ASSERT_EQ(rho.size(), 1u);
    EXPECT_EQ(rho[0], 1600.0);
  }
}

// The data cards of an LS-DYNA keyword in fixed format: every line after the
// keyword and its title, cut into fields of @p width columns. Checks that no
// line is longer than 8 fields (what LS-DYNA reads; the rest is ignored).
std::vector<std::vector<double>> fixedFormatCards(const std::string& text, int width) {
  std::vector<std::vector<double>> cards;
  std::istringstream in(text);
  std::string line;
  bool started = false;
  while (std::getline(in, line)) {
    if (line.rfind("*MAT_ANISOTROPIC_ELASTIC", 0) == 0) {
      started = true;
      std::getline(in, line); // title line
      continue;
    }
    if (!started || line.empty() || line[0] == '$')
      continue;
    EXPECT_LE(line.size(), static_cast<std::size_t>(8 * width)) << line;
    std::vector<double> values;
    for (std::size_t k = 0; k < line.size(); k += static_cast<std::size_t>(width))
      values.push_back(std::stod(line.substr(k, static_cast<std::size_t>(width))));
    cards.push_back(values);
  }
  return cards;
}

// LS-DYNA *MAT_ANISOTROPIC_ELASTIC card 1: MID RO C11 C12 C22 C13 C23 C33,
// card 2: C14 C24 C34 C44 C15 C25 C35 C45, card 3: C55 C16 C26 C36 C46 C56
// C66 AOPT, order xx yy zz xy yz zx: C44 = 80, C55 = 20, C66 = 30 GPa. Large
// format ("+" suffix) has 20-column fields, standard format 10 columns.
TEST_F(MaterialsProgram, LsdynaCardFollowsManualOrder) {
  ASSERT_EQ(run("add t1 --from-catalog table1-anisotropic").status, 0);
  for (const auto& [format, width] :
       {std::pair<std::string, int>{"lsdyna", 20}, {"lsdyna-small", 10}}) {
    const auto r = run("export t1 --format " + format);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(width == 20 ? "*MAT_ANISOTROPIC_ELASTIC_TITLE+\n"
                                     : "*MAT_ANISOTROPIC_ELASTIC_TITLE\n"),
              std::string::npos)
        << r.out;
    const auto cards = fixedFormatCards(r.out, width);
    ASSERT_GE(cards.size(), 3u) << r.out;
    ASSERT_EQ(cards[0].size(), 8u);
    ASSERT_EQ(cards[1].size(), 8u);
    ASSERT_EQ(cards[2].size(), 8u);
    EXPECT_EQ(cards[0][1], 1600.0); // RO
    const double c1[6] = {150, 40, 150, 10, 80, 150};
    for (int k = 0; k < 6; ++k)
      EXPECT_EQ(cards[0][static_cast<std::size_t>(k + 2)], c1[k] * GPa) << format;
    const double c2[8] = {0, 0, 0, 80, 0, 0, 0, 0};
    for (int k = 0; k < 8; ++k)
      EXPECT_EQ(cards[1][static_cast<std::size_t>(k)], c2[k] * GPa) << format;
    const double c3[7] = {20, 0, 0, 0, 0, 0, 30};
    for (int k = 0; k < 7; ++k)
      EXPECT_EQ(cards[2][static_cast<std::size_t>(k)], c3[k] * GPa) << format;
    EXPECT_EQ(cards[2][7], 2.0); // AOPT = 2: material axes from A = x, D = y
  }
}

// Homogenized entries carry 17-digit constants of any sign: the cards must
// still respect each reader's line limits (LS-DYNA 8 fields of 20 or 10
// columns, CalculiX 132 columns, Abaqus 256) and keep the digits the format
// allows: 17 for Abaqus, 9 for CalculiX (relative 5e-9), 13 or more for
// LS-DYNA large format (1e-12), 3 for a negative value in 9 characters of
// standard format ("-1.84E+10": relative 5e-3).
TEST_F(MaterialsProgram, CardsOfFullPrecisionConstantsFitTheirReaders) {
  std::mt19937_64 rng(99);
  const mat::Matrix6 c = lamina::test::randomSpd(rng); // negative off-diagonals too
  std::ostringstream constants;
  constants.precision(17);
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j)
      constants << (i || j ? "," : "") << c(i, j);
  ASSERT_EQ(run("add full --constants " + constants.str() + " --density 1234.5678901234567").status,
            0);
  const mat::Matrix6 stored = mat::Library(lib_).get("full").C.matrix();
  for (const auto& [format, width, tol] :
       {std::tuple<std::string, int, double>{"lsdyna", 20, 1e-12}, {"lsdyna-small", 10, 5e-3}}) {
    const auto r = run("export full --format " + format);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto cards = fixedFormatCards(r.out, width);
    ASSERT_GE(cards.size(), 3u);
    const std::vector<double> v{
        cards[0][2], cards[0][3], cards[0][4], cards[0][5], cards[0][6], cards[0][7], cards[1][0],
        cards[1][1], cards[1][2], cards[1][3], cards[1][4], cards[1][5], cards[1][6], cards[1][7],
        cards[2][0], cards[2][1], cards[2][2], cards[2][3], cards[2][4], cards[2][5], cards[2][6]};
    const auto expected = mat::lsdynaCardValues(stored);
    for (std::size_t k = 0; k < 21; ++k)
      EXPECT_NEAR(v[k], expected[k], tol * std::abs(expected[k])) << format << " value #" << k + 1;
  }
  for (const auto& [format, limit, keyword, tol] :
       {std::tuple<std::string, std::size_t, std::string, double>{
            "abaqus", 256, "*ELASTIC, TYPE=ANISOTROPIC", 0.0},
        {"calculix", 132, "*ELASTIC, TYPE=ANISO", 5e-9}}) {
    const auto r = run("export full --format " + format);
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream in(r.out);
    std::string line;
    while (std::getline(in, line))
      EXPECT_LE(line.size(), limit) << format << ": " << line;
    const std::vector<double> v = cardNumbers(r.out, keyword);
    ASSERT_EQ(v.size(), 21u) << r.out;
    const auto expected = mat::abaqusCardValues(stored);
    for (std::size_t k = 0; k < 21; ++k)
      EXPECT_NEAR(v[k], expected[k], tol * std::abs(expected[k])) << format << " value #" << k + 1;
  }
}

TEST_F(MaterialsProgram, ExportJsonEqualsShowJson) {
  ASSERT_EQ(run("add glass --from-catalog e-glass").status, 0);
  const auto r = run("export glass --format json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out), showJson("glass"));
}

TEST_F(MaterialsProgram, ListAndRemove) {
  ASSERT_EQ(run("add a --from-catalog e-glass").status, 0);
  ASSERT_EQ(run("add b --from-catalog aramid").status, 0);
  auto r = run("list");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("a  catalog  isotropic"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("b  catalog  transversely isotropic"), std::string::npos) << r.out;
  ASSERT_EQ(run("remove a").status, 0);
  EXPECT_EQ(mat::Library(lib_).names(), std::vector<std::string>{"b"});
  // The human table prints as well.
  r = run("show b");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("transversely isotropic (axis x)"), std::string::npos) << r.out;
}

// Two processes each add 20 entries at once through Library::add (forked
// children): the lock serializes the read-modify-write cycles, so all 40 land.
TEST(ConcurrentWriters, ForkedProcessesBothLand) {
  TempDir dir;
  const auto path = dir / "library.toml";
  const int perChild = 20;
  std::vector<pid_t> kids;
  for (const char* prefix : {"left", "right"})
    kids.push_back(lamina::test::forkChild([&path, prefix] {
      for (int k = 0; k < perChild; ++k) {
        mat::Material m;
        m.name = std::string(prefix) + std::to_string(k);
        m.C = mat::Stiffness::isotropic(1e9 * (k + 1), 0.25);
        m.density = 1000 + k;
        mat::Library(path).add(m);
      }
    }));
  lamina::test::expectChildrenSucceed(kids);
  const mat::Library lib(path);
  EXPECT_EQ(lib.names().size(), static_cast<std::size_t>(2 * perChild));
  for (int k = 0; k < perChild; ++k) {
    EXPECT_TRUE(lib.contains("left" + std::to_string(k)));
    EXPECT_TRUE(lib.contains("right" + std::to_string(k)));
  }
  EXPECT_EQ(lib.get("right7").density, 1007.0);
}

// Two shells run `materials add` 20 times each, concurrently: 40 entries.
TEST(ConcurrentWriters, TwoMaterialsCommandsBothLand) {
  TempDir dir;
  const auto path = dir / "library.toml";
  const std::string prog = lamina::test::materialsProgram();
  const std::string iso = // steel-like isotropic constants, upper triangle row by row
      "2.8e11,1.2e11,1.2e11,0,0,0,2.8e11,1.2e11,0,0,0,2.8e11,0,0,0,8e10,0,0,8e10,0,8e10";
  auto loop = [&](const std::string& prefix) {
    return "( for i in $(seq 1 20); do '" + prog + "' --library '" + path.string() + "' add " +
           prefix + "$i --constants " + iso + " --density 7850 2>/dev/null || echo FAIL" + prefix +
           "$i; done )";
  };
  const std::string cmd = loop("p") + " > '" + (dir / "p.out").string() + "' & " + loop("q") +
                          " > '" + (dir / "q.out").string() + "' & wait";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(lamina::test::readFile(dir / "p.out"), "");
  EXPECT_EQ(lamina::test::readFile(dir / "q.out"), "");
  const mat::Library lib(path);
  EXPECT_EQ(lib.names().size(), 40u);
  for (int k = 1; k <= 20; ++k) {
    EXPECT_TRUE(lib.contains("p" + std::to_string(k)));
    EXPECT_TRUE(lib.contains("q" + std::to_string(k)));
  }
}

// A writer killed (SIGKILL) at arbitrary moments never leaves the library
// unreadable or loses an entry it had written: the file always parses and
// holds exactly the entries w0 .. w(n-1) for some n; the kernel drops the
// dead writer's lock, so the next add succeeds.
TEST(ConcurrentWriters, KilledWriterLeavesReadableLibrary) {
  TempDir dir;
  const auto path = dir / "library.toml";
  std::size_t previous = 0;
  for (int round = 0; round < 3; ++round) {
    const pid_t pid = lamina::test::forkChild([&path] {
      mat::Library lib(path);
      for (std::size_t k = lib.names().size(); k < 100000; ++k) {
        mat::Material m;
        m.name = "w" + std::to_string(k);
        m.C = mat::Stiffness::isotropic(1e9, 0.3);
        m.density = 1000;
        lib.add(m);
      }
    });
    // Wait until the writer has landed at least one entry of this round
    // (robust to a loaded machine), then kill it a little later, mid-work.
    for (int wait = 0; wait < 2000; ++wait) {
      if (std::filesystem::exists(path) && mat::Library(path).names().size() > previous)
        break;
      ::usleep(5000);
    }
    ::usleep(static_cast<useconds_t>(3000 + 7000 * round));
    ::kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status)) << "the writer finished before it was killed";
    const mat::Library lib(path); // throws if the file were torn
    const std::size_t n = lib.names().size();
    EXPECT_GE(n, previous);
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_TRUE(lib.contains("w" + std::to_string(k))) << k << " of " << n;
    previous = n;
  }
  EXPECT_GT(previous, 0u);
  mat::Material m;
  m.name = "after";
  m.C = mat::Stiffness::isotropic(1e9, 0.3);
  m.density = 1000;
  mat::Library(path).add(m);
  EXPECT_TRUE(mat::Library(path).contains("after"));
}

// `materials drive` (the material-point driver's interface): the exact header, one row per step
// plus t = 0, time = strain / rate, the driven column as asked; a library
// entry drives as linear elasticity (sigma_xy = C44 gamma exactly at any
// rate); --library after the subcommand is accepted.
TEST_F(MaterialsProgram, DriveWritesTheDocumentedCsv) {
  const auto csv = dir_ / "drive.csv";
  auto r = run("drive polyurea-gvbo --path shear --rate 1e3 --to 0.1 --steps 10 --out '" +
               csv.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream in(lamina::test::readFile(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,eps_xx,eps_yy,eps_zz,eps_xy,eps_yz,eps_xz,sig_xx,sig_yy,sig_zz,sig_xy,sig_yz,"
                  "sig_xz");
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream items(line);
    std::string item;
    while (std::getline(items, item, ','))
      v.push_back(std::stod(item));
    ASSERT_EQ(v.size(), 13u) << line;
    rows.push_back(v);
  }
  ASSERT_EQ(rows.size(), 11u);
  EXPECT_DOUBLE_EQ(rows.back()[0], 0.1 / 1e3);
  EXPECT_DOUBLE_EQ(rows.back()[4], 0.1);
  EXPECT_EQ(rows.back()[1], 0.0);
  EXPECT_GT(rows.back()[10], 0.0);
  // a library entry: linear elastic, sigma_xy = C44 gamma in small strain
  ASSERT_EQ(run("add glass --from-catalog e-glass").status, 0);
  const auto csv2 = dir_ / "glass.csv";
  r = lamina::test::runMaterials(
      dir_, dir_ / "other.toml",
      "drive glass --path shear --rate 1e6 --to 0.001 --steps 4 --kinematics small --library '" +
          lib_.string() + "' --out '" + csv2.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = lamina::test::readFile(csv2);
  std::istringstream lastLine(text.substr(text.rfind('\n', text.size() - 2) + 1));
  std::vector<double> last;
  for (std::string item; std::getline(lastLine, item, ',');)
    last.push_back(std::stod(item));
  ASSERT_EQ(last.size(), 13u);
  const double C44 = 72.4e9 / (2 * 1.22); // E / (2 (1 + nu)) of e-glass
  EXPECT_NEAR(last[10], C44 * 0.001, 1e-9 * C44 * 0.001);
  // biaxial stress on the command line: sigma_xx = sigma_yy = E/(1 - nu) e,
  // sigma_zz ~ 0 (drive's tolerance 1e-10 of sigma_xx + 1e-6 Pa)
  const auto csv3 = dir_ / "biaxial.csv";
  r = run("drive glass --path biaxial-stress --rate 1 --to 0.001 --steps 4 --kinematics small "
          "--out '" +
          csv3.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text3 = lamina::test::readFile(csv3);
  std::istringstream biaxLine(text3.substr(text3.rfind('\n', text3.size() - 2) + 1));
  std::vector<double> biax;
  for (std::string item; std::getline(biaxLine, item, ',');)
    biax.push_back(std::stod(item));
  ASSERT_EQ(biax.size(), 13u);
  const double Eb = 72.4e9 / (1 - 0.22) * 0.001; // e-glass biaxial modulus times e
  EXPECT_NEAR(biax[7], Eb, 1e-9 * Eb);
  EXPECT_NEAR(biax[8], Eb, 1e-9 * Eb);
  EXPECT_LE(std::abs(biax[9]), 1e-10 * Eb + 1e-6);
  // bad input: unknown path, unknown material
  EXPECT_EQ(run("drive polyurea-gvbo --path twist --rate 1 --to 0.1 --out x.csv").status, 2);
  r = run("drive no-such --path shear --rate 1 --to 0.1 --out '" + (dir_ / "x.csv").string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no-such"), std::string::npos) << r.err;
}
