/// @file reduced_order_library_test.cpp
/// @brief Reduced-order entries in the library: an entry (phases, side file,
/// checksum) survives serialize/parse exactly, Library::add records the
/// checksum of every side file it writes, and the law read through
/// MaterialSource gives the stress of the law built directly from the cell.

#include "reduced_order_cells.hpp"

#include "materials/gvbo_law.hpp"
#include "materials/material_source.hpp"
#include "materials/reduced_order_law.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

namespace lamina {
namespace {

namespace mat = materials;
using mat::Vector6;

TEST(ReducedOrderLibrary, EntryRoundTripsExactly) {
  const mat::ReducedOrderModel model = test::polyureaLaminate();
  mat::Material m = test::reducedOrderEntry("polyurea-cell", model);
  m.phases[0].name = "soft \"domain\""; // a cell file's phase name, quoted when written
  m.side_file = "library.side/cell.abc123.h5";
  m.side_checksum = "fnv1a64:0123456789abcdef";
  const std::string text = mat::Library::serialize({{m.name, m}});
  const auto parsed = mat::Library::parse(text, "library.toml");
  ASSERT_EQ(parsed.count(m.name), 1u);
  const mat::Material& r = parsed.at(m.name);
  EXPECT_EQ(r.kind, "reduced-order");
  EXPECT_EQ(r.side_file, m.side_file);
  EXPECT_EQ(r.side_checksum, m.side_checksum);
  ASSERT_EQ(r.phases.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(r.phases[p].name, m.phases[p].name);
    EXPECT_EQ(r.phases[p].density, m.phases[p].density);
    EXPECT_EQ(r.phases[p].law.C.matrix(), m.phases[p].law.C.matrix()) << "bit for bit";
  }
  // GVBO: all 15 parameters bit for bit; the elastic phase is its C
  EXPECT_EQ(r.phases[0].law.kind, mat::LawKind::Gvbo);
  ASSERT_TRUE(r.phases[0].law.gvbo.has_value());
  const mat::GvboParameters &a = *r.phases[0].law.gvbo, &b = *m.phases[0].law.gvbo;
  EXPECT_EQ(a.E0, b.E0);
  EXPECT_EQ(a.nu0, b.nu0);
  for (const auto& [key, member] : mat::gvboTableKeys())
    EXPECT_EQ(a.*member, b.*member) << key;
  EXPECT_EQ(r.phases[1].law.kind, mat::LawKind::Anisotropic);
  EXPECT_FALSE(r.phases[1].law.gvbo.has_value());
  // and the text is a fixed point
  EXPECT_EQ(mat::Library::serialize(parsed), text);
}

TEST(ReducedOrderLibrary, AddRecordsTheChecksumOfEverySideFile) {
  test::TempDir dir;
  const auto lib = dir.path() / "library.toml";
  test::addReducedOrderEntry(lib, "cell", test::polyureaLaminate());
  mat::Material h; // a homogenized entry with a side file of its own
  h.name = "homogenized";
  h.kind = "homogenized";
  h.C = mat::Stiffness::isotropic(1e9, 0.3);
  h.density = 1000;
  mat::Library(lib).add(h, false,
                        [](const std::filesystem::path& p) { test::writeFile(p, "any bytes"); });
  const mat::Library reread(lib);
  for (const std::string name : {"cell", "homogenized"}) {
    const mat::Material& m = reread.get(name);
    ASSERT_FALSE(m.side_file.empty()) << name;
    EXPECT_EQ(m.side_checksum, mat::fileChecksum(reread.folder() / m.side_file)) << name;
  }
}

TEST(ReducedOrderLibrary, LawThroughMaterialSourceEqualsTheLawBuiltDirectly) {
  test::TempDir dir;
  const auto lib = dir.path() / "library.toml";
  const mat::ReducedOrderModel model = test::polyureaLaminate(true);
  test::addReducedOrderEntry(lib, "cell", model);
  mat::MaterialSource source(lib.string(), test::catalogPath());
  const mat::LawPtr read = source.law("cell");
  ASSERT_EQ(read->kind(), mat::LawKind::ReducedOrder);
  const mat::ReducedOrderLaw direct("cell", model);
  ASSERT_EQ(read->stateSize(), direct.stateSize());
  std::vector<double> s1(static_cast<std::size_t>(direct.stateSize())), s2(s1.size());
  read->initState(s1.data());
  direct.initState(s2.data());
  Vector6 dir6;
  dir6 << -0.05, 0.01, 0.02, 0.04, -0.01, 0.03;
  for (int i = 0; i < 10; ++i) {
    const mat::PointStep s{dir6 * i / 10.0, dir6 * (i + 1) / 10.0, 1, 1, 1e-2};
    Vector6 a, b;
    mat::Matrix6 Ta, Tb;
    read->update(s, s1.data(), s1.data(), a, &Ta);
    direct.update(s, s2.data(), s2.data(), b, &Tb);
    EXPECT_EQ(a, b) << "step " << i; // the same numbers, read back bit for bit
    EXPECT_EQ(Ta, Tb) << "step " << i;
  }
  EXPECT_EQ(s1, s2);
}

} // namespace
} // namespace lamina
