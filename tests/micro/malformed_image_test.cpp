/// @file malformed_image_test.cpp
/// @brief Image files that do not hold what their headers say, and image
/// paths that are not files. A stack, array or dataset cut short is refused
/// naming the image and what is missing, never read as a smaller image:
/// each cut tried of a TIFF stack and of a VTI file (every 2nd, every 3rd
/// byte) either fails or (a cut in bytes no reader needs) gives the whole
/// image back. FIFOs, directories,
/// sockets and devices given as an image or a cell file are refused at once.

#include "../core/test_util.hpp"
#include "core/hdf5_file.hpp"
#include "micro/cell.hpp"
#include "micro/image_io.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <tiffio.h>

#include <unistd.h>

namespace lamina::micro {
namespace {

using test::errorOf;
using test::TempDir;

/// A 5 x 4 x 6 image of labels 0, 7, 9 (distinct sizes expose an axis mix-up).
VoxelImage pattern() {
  VoxelImage img;
  img.n = {5, 4, 6};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 6; ++k)
        img.value.push_back(std::array<int, 3>{0, 7, 9}[(i + 2 * j + 3 * k) % 3]);
  return img;
}

/// The image source of a cell naming @p path in @p format.
ImageSource sourceOf(const std::filesystem::path& path, ImageFormat format) {
  ImageSource s;
  s.path = path;
  s.format = format;
  s.cell_file = "cell.toml";
  if (format == ImageFormat::Raw) {
    s.dimensions = {5, 4, 6};
    s.axes = AxisOrder::Zyx;
  }
  return s;
}

/// Copies the first @p bytes of @p from to @p to.
void cutCopy(const std::filesystem::path& from, const std::filesystem::path& to,
             std::size_t bytes) {
  test::writeFile(to, test::readFile(from).substr(0, bytes));
}

/// Reads every @p stride-th cut of the @p format file @p whole (lengths 0,
/// stride, ... below its size): each must be refused naming the image, or
/// read back as the whole image. @return how many cuts were refused
int refusedCuts(const TempDir& dir, const std::filesystem::path& whole, ImageFormat format,
                std::size_t stride = 1) {
  const std::size_t size = std::filesystem::file_size(whole);
  const auto cut = dir / ("cut" + whole.extension().string());
  const VoxelImage expect = pattern();
  int refused = 0;
  for (std::size_t n = 0; n < size; n += stride) {
    cutCopy(whole, cut, n);
    try {
      const VoxelImage got = readImage(sourceOf(cut, format));
      EXPECT_EQ(got.n, expect.n) << "cut at " << n << " of " << size;
      EXPECT_EQ(got.value, expect.value) << "cut at " << n << " of " << size;
    } catch (const Error& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find(cut.string()), std::string::npos) << e.what();
    }
  }
  return refused;
}

// The reproducer and its class: a multi-page TIFF cut anywhere was
// read as fewer pages (another cell, another C, exit 0). Every cut now
// fails or yields the whole stack; a cut inside page 3 names the page.
TEST(TruncatedImages, TiffStackCutAnywhereIsNeverFewerPages) {
  TempDir dir;
  const auto whole = dir / "stack.tif";
  writeImage(pattern(), whole, ImageFormat::Tiff);
  // every other cut (of about 1100 bytes; the stride halves the time)
  const int refused = refusedCuts(dir, whole, ImageFormat::Tiff, 2);
  // all but a few bytes of padding past the last directory are needed
  EXPECT_GE(refused, static_cast<int>(std::filesystem::file_size(whole)) / 2 - 4);
  cutCopy(whole, dir / "half.tif", std::filesystem::file_size(whole) / 2);
  const std::string msg =
      errorOf([&] { readImage(sourceOf(dir / "half.tif", ImageFormat::Tiff)); });
  EXPECT_NE(msg.find("truncated TIFF stack"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cell.image"), std::string::npos) << msg;
}

/// Writes a 5 x 4 x @p pages 8-bit stack through libtiff without a
/// PageNumber tag (as many scanners and ImageJ do); page 0 carries the
/// ImageDescription @p description when it is not empty.
void writePlainStack(const std::filesystem::path& path, int pages,
                     const std::string& description = "") {
  TIFF* t = TIFFOpen(path.c_str(), "w");
  ASSERT_NE(t, nullptr);
  for (int k = 0; k < pages; ++k) {
    if (k == 0 && !description.empty())
      TIFFSetField(t, TIFFTAG_IMAGEDESCRIPTION, description.c_str());
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, 5);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, 4);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 4);
    for (std::uint32_t j = 0; j < 4; ++j) {
      std::uint8_t row[5] = {0, 7, 9, 0, 7};
      ASSERT_GE(TIFFWriteScanline(t, row, j, 0), 0);
    }
    TIFFWriteDirectory(t);
  }
  TIFFClose(t);
}

// Without a declared page count, the directory chain itself tells a cut:
// the last page read points to one the file does not hold. The cell's
// `dimensions` is checked against the stack as well, by read and by probe,
// and so is the count of ImageJ's description ("images=7" over 6 pages).
TEST(TruncatedImages, TiffWithoutPageCountBrokenChainAndDeclaredDepth) {
  TempDir dir;
  writePlainStack(dir / "s.tif", 6);
  const std::size_t size = std::filesystem::file_size(dir / "s.tif");
  int refused = 0;
  for (std::size_t n = size / 3; n < size - 16; n += 7) {
    cutCopy(dir / "s.tif", dir / "c.tif", n);
    const std::string msg =
        errorOf([&] { readImage(sourceOf(dir / "c.tif", ImageFormat::Tiff)); });
    refused += !msg.empty();
    EXPECT_NE(msg.find("c.tif"), std::string::npos) << "cut at " << n << ": " << msg;
  }
  EXPECT_GT(refused, 0);
  ImageSource s = sourceOf(dir / "s.tif", ImageFormat::Tiff);
  EXPECT_EQ(readImage(s).n, (std::array<int, 3>{5, 4, 6}));
  s.dimensions = {5, 4, 7};
  for (const auto& f : std::vector<std::function<void()>>{[&] { readImage(s); },
                                                         [&] { imageShape(s); }}) {
    const std::string msg = errorOf(f);
    EXPECT_NE(msg.find("holds 5 x 4 x 6 voxels, the cell declares 5 x 4 x 7"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("cell.dimensions"), std::string::npos) << msg;
  }
  writePlainStack(dir / "ij.tif", 6, "ImageJ=1.54f\nimages=7\nslices=7\n");
  const std::string msg = errorOf([&] { readImage(sourceOf(dir / "ij.tif", ImageFormat::Tiff)); });
  EXPECT_NE(msg.find("declares 7 pages, the file holds 6"), std::string::npos) << msg;
  writePlainStack(dir / "ij6.tif", 6, "ImageJ=1.54f\nimages=6\nslices=6\n");
  EXPECT_EQ(readImage(sourceOf(dir / "ij6.tif", ImageFormat::Tiff)).n[2], 6);
}

// VTI (appended raw, zlib, as micro writes it): every third cut (the
// stride keeps the test well under a second) fails or gives the whole image.
TEST(TruncatedImages, VtiCutAnywhereIsRefused) {
  TempDir dir;
  for (const bool zlib : {false, true}) {
    ImageWriteOptions o;
    o.zlib = zlib;
    writeImage(pattern(), dir / "v.vti", ImageFormat::Vti, o);
    EXPECT_GT(refusedCuts(dir, dir / "v.vti", ImageFormat::Vti, 3), 0);
  }
}

// A VTI whose appended byte count is 2^64 - 1 (found by image_fuzzer: the
// count plus its header wrapped to a small number and the copy ran past
// the file) is refused as truncated, naming the image.
TEST(TruncatedImages, VtiHugeByteCountIsTruncationNotOverflow) {
  TempDir dir;
  writeImage(pattern(), dir / "v.vti", ImageFormat::Vti);
  std::string text = test::readFile(dir / "v.vti");
  const std::size_t marker = text.find('_', text.find("<AppendedData"));
  ASSERT_NE(marker, std::string::npos);
  text.replace(marker + 1, 8, std::string(8, '\xff')); // the UInt64 byte count
  test::writeFile(dir / "big.vti", text);
  const std::string msg =
      errorOf([&] { readImage(sourceOf(dir / "big.vti", ImageFormat::Vti)); });
  EXPECT_NE(msg.find("truncated .vti file"), std::string::npos) << msg;
  EXPECT_NE(msg.find("big.vti"), std::string::npos) << msg;
}

// A VTI's integer attributes are read strictly: NumberOfComponents =
// "4294967297" was 1 (atoi), offset = "-5" wrapped to 2^64 - 5 and "x" was 0.
// Each is refused naming the image and the attribute.
TEST(TruncatedImages, VtiAttributesAreIntegersNotWrapped) {
  TempDir dir;
  writeImage(pattern(), dir / "v.vti", ImageFormat::Vti);
  const std::string text = test::readFile(dir / "v.vti");
  const std::size_t da = text.find("<DataArray");
  ASSERT_NE(da, std::string::npos);
  const std::size_t off = text.find("offset=\"", da);
  ASSERT_NE(off, std::string::npos);
  const std::size_t off_end = text.find('"', off + 8);
  for (const std::string bad : {"-5", "x", "18446744073709551621", "1e3"}) {
    std::string t = text;
    t.replace(off + 8, off_end - off - 8, bad);
    test::writeFile(dir / "bad.vti", t);
    const std::string msg =
        errorOf([&] { readImage(sourceOf(dir / "bad.vti", ImageFormat::Vti)); });
    EXPECT_NE(msg.find("offset"), std::string::npos) << bad << ": " << msg;
    EXPECT_NE(msg.find("bad.vti"), std::string::npos) << msg;
  }
  std::string t = text;
  t.insert(da + 10, " NumberOfComponents=\"4294967297\"");
  test::writeFile(dir / "bad.vti", t);
  const std::string msg =
      errorOf([&] { readImage(sourceOf(dir / "bad.vti", ImageFormat::Vti)); });
  EXPECT_NE(msg.find("NumberOfComponents"), std::string::npos) << msg;
}

// Raw: every cut is short of dimensions x type; dimensions whose byte count
// overflows 64 bits are refused as needing more than the file, not wrapped.
TEST(TruncatedImages, RawCutAndOverflowingDimensions) {
  TempDir dir;
  writeImage(pattern(), dir / "r.raw", ImageFormat::Raw);
  const std::size_t size = std::filesystem::file_size(dir / "r.raw");
  EXPECT_EQ(refusedCuts(dir, dir / "r.raw", ImageFormat::Raw), static_cast<int>(size));
  ImageSource s = sourceOf(dir / "r.raw", ImageFormat::Raw);
  s.dimensions = {1000000000, 1000000000, 1000000000};
  s.type = ScalarType::UInt64;
  const std::string msg = errorOf([&] { readImage(s); });
  EXPECT_NE(msg.find("truncated raw file"), std::string::npos) << msg;
}

/// Creates /phases (5 x 4 x 6 int32) in @p path: chunked (chunks of 5 x 4 x
/// 1) with only the first chunk written, or contiguous and never written.
void writePartialDataset(const std::filesystem::path& path, bool chunked) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[3] = {5, 4, 6}, chunk[3] = {5, 4, 1};
  const hid_t space = H5Screate_simple(3, dims, nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (chunked)
    H5Pset_chunk(dcpl, 3, chunk);
  const hid_t set = H5Dcreate2(f, "/phases", H5T_NATIVE_INT32, space, H5P_DEFAULT, dcpl,
                               H5P_DEFAULT);
  if (chunked) {
    const hsize_t start[3] = {0, 0, 0};
    const hid_t mem = H5Screate_simple(3, chunk, nullptr);
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, chunk, nullptr);
    const std::vector<std::int32_t> ones(20, 7);
    H5Dwrite(set, H5T_NATIVE_INT32, mem, space, H5P_DEFAULT, ones.data());
    H5Sclose(mem);
  }
  H5Dclose(set);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(f);
}

// HDF5: a cut file (HDF5's own end-of-file check, reported as truncation),
// a chunked dataset with unwritten chunks and a contiguous one never
// written (both read as fill values before) are refused naming the dataset.
TEST(TruncatedImages, Hdf5CutFileAndUnwrittenData) {
  TempDir dir;
  writeImage(pattern(), dir / "h.h5", ImageFormat::Hdf5);
  cutCopy(dir / "h.h5", dir / "c.h5", std::filesystem::file_size(dir / "h.h5") - 100);
  std::string msg = errorOf([&] { readImage(sourceOf(dir / "c.h5", ImageFormat::Hdf5)); });
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  EXPECT_NE(msg.find("c.h5"), std::string::npos) << msg;
  writePartialDataset(dir / "chunked.h5", true);
  msg = errorOf([&] { readImage(sourceOf(dir / "chunked.h5", ImageFormat::Hdf5)); });
  EXPECT_NE(msg.find("stores 1 of its 6 chunks"), std::string::npos) << msg;
  writePartialDataset(dir / "contiguous.h5", false);
  msg = errorOf([&] { readImage(sourceOf(dir / "contiguous.h5", ImageFormat::Hdf5)); });
  EXPECT_NE(msg.find("needs 480 bytes of labels"), std::string::npos) << msg;
}

// Image paths and cell files that are not regular files: refused at once,
// naming the path and what it is (a FIFO without a writer blocked before).
TEST(NotRegularImages, EveryFormatAndTheCellFileRefuseNonFiles) {
  const test::HangGuard guard(20);
  TempDir dir;
  for (const auto& [suffix, format] :
       std::vector<std::pair<std::string, ImageFormat>>{{".tif", ImageFormat::Tiff},
                                                        {".vti", ImageFormat::Vti},
                                                        {".raw", ImageFormat::Raw},
                                                        {".h5", ImageFormat::Hdf5}}) {
    for (const auto& p : test::notRegularFiles(dir, suffix)) {
      for (const auto& f : std::vector<std::function<void()>>{
               [&] { readImage(sourceOf(p, format)); }, [&] { imageShape(sourceOf(p, format)); }}) {
        const std::string msg = errorOf(f);
        EXPECT_NE(msg.find("image " + p.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
        EXPECT_NE(msg.find("cell.toml"), std::string::npos) << msg;
      }
    }
  }
  for (const auto& p : test::notRegularFiles(dir, ".toml")) {
    const std::string msg = errorOf([&] { readCell(p, lazyCatalog()); });
    EXPECT_NE(msg.find(p.string() + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
  }
}

} // namespace
} // namespace lamina::micro
