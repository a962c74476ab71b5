// Voxel images in: files written by independent writers (h5py, VTK XML laid
// out by hand in Python, libtiff called here) read into the known pattern;
// each format micro writes reads back to the same phase map (round trip);
// crop and down-sampling against hand-counted results; clear errors for a
// wrong dataset, an id with no phase, a size mismatch, a truncated file and
// an image that does not fit in memory.

#include "../core/test_util.hpp"
#include "micro/cell.hpp"
#include "micro/image_cell.hpp"
#include "micro/image_io.hpp"
#include "micro/phase_map_io.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>
#include <tiffio.h>

#include <cstdlib>

namespace lamina::micro {
namespace {

using test::errorOf;
using test::TempDir;
using test::writeFile;

constexpr int NX = 5, NY = 4, NZ = 3;
constexpr int kIds[3] = {0, 7, 9};

/// The pattern of tests/micro/write_images.py: ID[(i + 2 j + 3 k) % 3].
int patternLabel(int i, int j, int k) {
  return kIds[(i + 2 * j + 3 * k) % 3];
}

/// Three phases owning the ids 0, 7, 9 (phase index 0, 1, 2).
const std::string kPhases =
    "[[phases]]\nname = \"m\"\nid = 0\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n"
    "[[phases]]\nname = \"a\"\nid = 7\nlaw = \"isotropic\"\nE = 2e9\nnu = 0.3\ndensity = 1000\n"
    "[[phases]]\nname = \"b\"\nid = 9\nlaw = \"isotropic\"\nE = 3e9\nnu = 0.3\ndensity = 1000\n";

CellSpec imageCell(const TempDir& dir, const std::string& cell_keys,
                   const std::string& phases = kPhases) {
  const std::string text = "[cell]\n" + cell_keys + "\n" + phases;
  return readCellString(text, (dir / "cell.toml").string(), lazyCatalog());
}

/// Expects @p cell to hold the pattern as phase indices (id 0, 7, 9 -> 0, 1, 2).
void expectPattern(const UnitCell& cell) {
  ASSERT_EQ(cell.n, (std::array<int, 3>{NX, NY, NZ}));
  int wrong = 0;
  for (int i = 0; i < NX; ++i)
    for (int j = 0; j < NY; ++j)
      for (int k = 0; k < NZ; ++k)
        wrong += cell.phase[cell.index(i, j, k)] != (i + 2 * j + 3 * k) % 3;
  EXPECT_EQ(wrong, 0);
}

class IndependentWriters : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const std::string cmd = "/usr/bin/python3 " LAMINA_SOURCE_DIR "/tests/micro/write_images.py " +
                            dir_->path().string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << "needs /usr/bin/python3 with numpy and h5py";
  }
  static void TearDownTestSuite() { delete dir_; }
  static TempDir* dir_;
};
TempDir* IndependentWriters::dir_ = nullptr;

TEST_F(IndependentWriters, Hdf5ByH5pyInBothAxisOrders) {
  const CellSpec xyz = imageCell(*dir_, "image = \"scan.h5\"\ndataset = \"/scan/labels\"");
  expectPattern(buildCell(xyz));
  const CellSpec zyx =
      imageCell(*dir_, "image = \"scan.h5\"\ndataset = \"/scan/zyx\"\naxes = \"zyx\"");
  expectPattern(buildCell(zyx));
}

TEST_F(IndependentWriters, VtiAsciiBinaryAppendedZlibCellAndPointData) {
  for (const char* f :
       {"ascii.vti", "point.vti", "binary.vti", "appended.vti", "zlib.vti", "zlib-appended.vti"}) {
    SCOPED_TRACE(f);
    const CellSpec s = imageCell(
        *dir_, std::string("image = \"") + f + "\"" +
                   (std::string(f) == "zlib-appended.vti" ? "\ndataset = \"labels\"" : ""));
    const UnitCell c = buildCell(s);
    expectPattern(c);
    // Spacing="0.5 0.5 2" of the file gives the cell size
    EXPECT_DOUBLE_EQ(c.size[0], 0.5 * NX);
    EXPECT_DOUBLE_EQ(c.size[2], 2.0 * NZ);
  }
}

TEST_F(IndependentWriters, RawBigEndianWithHeader) {
  const CellSpec s = imageCell(*dir_, "image = \"scan.raw\"\ndimensions = [5, 4, 3]\ntype = "
                                      "\"int16\"\nbyte_order = \"big\"\nheader_bytes = 16");
  expectPattern(buildCell(s));
}

// A 16-bit TIFF stack written here through libtiff itself (one page per z).
TEST(TiffStack, WrittenByLibtiff) {
  TempDir dir;
  TIFF* t = TIFFOpen((dir / "stack.tif").c_str(), "w");
  ASSERT_NE(t, nullptr);
  for (int k = 0; k < NZ; ++k) {
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, NX);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, NY);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 16);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 1);
    for (int j = 0; j < NY; ++j) {
      std::uint16_t row[NX];
      for (int i = 0; i < NX; ++i)
        row[i] = static_cast<std::uint16_t>(patternLabel(i, j, k));
      ASSERT_GE(TIFFWriteScanline(t, row, static_cast<std::uint32_t>(j), 0), 0);
    }
    TIFFWriteDirectory(t);
  }
  TIFFClose(t);
  expectPattern(buildCell(imageCell(dir, "image = \"stack.tif\"")));
}

// A generated cell written by micro in every format reads back through an
// image cell to the same phase map and cell size.
TEST(RoundTrip, GeneratedCellThroughEveryFormat) {
  TempDir dir;
  const std::string phases =
      "[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n"
      "[[phases]]\nname = \"s\"\nid = 300\nlaw = \"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = "
      "2000\n";
  const CellSpec gen = readCellString(
      "[cell]\nresolution = [12, 10, 8]\nsize = [1.2e-3, 1.0e-3, 0.8e-3]\n" + phases +
          "[[inclusions]]\nphase = \"s\"\nshape = \"sphere\"\nradius = 0.3e-3\n",
      (dir / "gen.toml").string(), lazyCatalog());
  const UnitCell cell = buildCell(gen);
  ASSERT_GT(cell.voxel_fraction[1], 0.05);
  const VoxelImage labels = labelImage(gen, cell);
  struct Case {
    const char* file;
    VtiEncoding enc;
    bool zlib;
  };
  for (const Case& c :
       {Case{"a.h5", VtiEncoding::Appended, false}, Case{"b.vti", VtiEncoding::Ascii, false},
        Case{"c.vti", VtiEncoding::Binary, false}, Case{"d.vti", VtiEncoding::Binary, true},
        Case{"e.vti", VtiEncoding::Appended, false}, Case{"f.vti", VtiEncoding::Appended, true},
        Case{"g.raw", VtiEncoding::Appended, false}, Case{"h.tif", VtiEncoding::Appended, false}}) {
    SCOPED_TRACE(c.file);
    ImageFormat fmt;
    ASSERT_TRUE(formatFromExtension(c.file, fmt));
    ImageWriteOptions wo;
    wo.vti = c.enc;
    wo.zlib = c.zlib;
    const std::string keys = writeImage(labels, dir / c.file, fmt, wo);
    const std::string ids = "[[phases]]\nname = \"m\"\nid = 0\nlaw = \"isotropic\"\nE = 1e9\nnu = "
                            "0.3\ndensity = 1000\n[[phases]]\nname = \"s\"\nid = 300\nlaw = "
                            "\"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = 2000\n";
    // raw and TIFF carry no voxel size: give it
    const std::string size =
        fmt == ImageFormat::Raw || fmt == ImageFormat::Tiff ? "voxel_size = 1e-4\n" : "";
    const UnitCell back = buildCell(imageCell(dir, keys + size, ids));
    EXPECT_EQ(back.n, cell.n);
    EXPECT_EQ(back.phase, cell.phase);
    EXPECT_NEAR((back.size - cell.size).norm(), 0, 1e-15);
  }
}

// crop keeps the window; downsample takes each 2^3 block's majority label
// (ties: the smallest label), checked against counts made here.
TEST_F(IndependentWriters, CropAndDownsample) {
  const CellSpec s = imageCell(*dir_, "image = \"scan.h5\"\ndataset = \"/scan/labels\"\ncrop = "
                                      "{ start = [1, 0, 1], count = [4, 4, 2] }");
  const UnitCell c = buildCell(s);
  ASSERT_EQ(c.n, (std::array<int, 3>{4, 4, 2}));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 2; ++k)
        EXPECT_EQ(c.phase[c.index(i, j, k)], (i + 1 + 2 * j + 3 * (k + 1)) % 3);
  const CellSpec d = imageCell(*dir_, "image = \"scan.h5\"\ndataset = \"/scan/labels\"\ncrop = "
                                      "{ start = [1, 0, 1], count = [4, 4, 2] }\ndownsample = 2");
  const UnitCell e = buildCell(d);
  ASSERT_EQ(e.n, (std::array<int, 3>{2, 2, 1}));
  for (int I = 0; I < 2; ++I)
    for (int J = 0; J < 2; ++J) {
      int votes[3] = {0, 0, 0};
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          for (int k = 0; k < 2; ++k)
            ++votes[(2 * I + a + 1 + 2 * (2 * J + b) + 3 * (k + 1)) % 3];
      int best = 0; // labels 0 < 7 < 9 follow the phase order: the first maximum wins ties
      for (int p = 1; p < 3; ++p)
        if (votes[p] > votes[best])
          best = p;
      EXPECT_EQ(e.phase[e.index(I, J, 0)], best) << I << " " << J;
    }
}

TEST_F(IndependentWriters, ClearErrors) {
  // wrong dataset: names it and lists what the file holds
  std::string m = errorOf([&] { imageCell(*dir_, "image = \"scan.h5\"\ndataset = \"/nope\""); });
  EXPECT_NE(m.find("no dataset '/nope'"), std::string::npos) << m;
  EXPECT_NE(m.find("/scan/labels"), std::string::npos) << m;
  EXPECT_NE(m.find("cell.dataset"), std::string::npos) << m;
  m = errorOf([&] { imageCell(*dir_, "image = \"scan.h5\"\ndataset = \"/scan/float\""); });
  EXPECT_NE(m.find("integer labels"), std::string::npos) << m;
  // an id with no phase: the value, its voxel count and the ids owned
  const std::string two =
      "[[phases]]\nname = \"m\"\nid = 0\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1\n"
      "[[phases]]\nname = \"a\"\nid = 7\nlaw = \"isotropic\"\nE = 2e9\nnu = 0.3\ndensity = 1\n";
  m = errorOf([&] { buildCell(imageCell(*dir_, "image = \"ascii.vti\"", two)); });
  int nines = 0;
  for (int i = 0; i < NX; ++i)
    for (int j = 0; j < NY; ++j)
      for (int k = 0; k < NZ; ++k)
        nines += patternLabel(i, j, k) == 9;
  EXPECT_NE(m.find("values no phase owns: 9 (" + std::to_string(nines) + " voxels)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("'phases'"), std::string::npos) << m;
  // a phase without id in an image cell
  m = errorOf([&] {
    imageCell(*dir_, "image = \"ascii.vti\"",
              "[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1\n");
  });
  EXPECT_NE(m.find("id = K"), std::string::npos) << m;
  // size mismatch: resolution against the image, raw dimensions against the file
  m = errorOf([&] { imageCell(*dir_, "image = \"ascii.vti\"\nresolution = [5, 4, 4]"); });
  EXPECT_NE(m.find("size mismatch"), std::string::npos) << m;
  m = errorOf([&] {
    buildCell(imageCell(*dir_, "image = \"scan.raw\"\ndimensions = [5, 4, 3]\ntype = \"int16\""));
  });
  EXPECT_NE(m.find("size mismatch"), std::string::npos) << m;
  // truncated: raw shorter than its dimensions, appended data cut in half
  m = errorOf([&] {
    buildCell(imageCell(*dir_, "image = \"scan.raw\"\ndimensions = [5, 4, 4]\ntype = \"int16\""));
  });
  EXPECT_NE(m.find("truncated raw file"), std::string::npos) << m;
  m = errorOf([&] { buildCell(imageCell(*dir_, "image = \"truncated.vti\"")); });
  EXPECT_NE(m.find("truncated .vti file"), std::string::npos) << m;
  // a scan that cannot fit (8192^3 voxels): says what it needs and suggests MPI,
  // before allocating anything
  m = errorOf([&] { buildCell(imageCell(*dir_, "image = \"huge.h5\"\ndataset = \"/labels\"")); });
  EXPECT_NE(m.find("needs"), std::string::npos) << m;
  EXPECT_NE(m.find("mpirun -np N homogenize"), std::string::npos) << m;
  // a missing file and keys of the wrong kind
  m = errorOf([&] { buildCell(imageCell(*dir_, "image = \"nothere.vti\"")); });
  EXPECT_NE(m.find("not found"), std::string::npos) << m;
  m = errorOf([&] { imageCell(*dir_, "image = \"ascii.vti\"\ntype = \"uint8\""); });
  EXPECT_NE(m.find("raw images only"), std::string::npos) << m;
  m = errorOf([&] {
    readCellString("[cell]\nresolution = 8\ndownsample = 2\n" + kPhases, "g.toml", lazyCatalog());
  });
  EXPECT_NE(m.find("image cells"), std::string::npos) << m;
}

} // namespace
} // namespace lamina::micro
