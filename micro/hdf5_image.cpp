// HDF5 voxel images: an integer dataset of rank 3 (see image_formats.hpp).

#include "core/atomic_file.hpp"
#include "core/hdf5_file.hpp"
#include "micro/image_formats.hpp"

#include <hdf5.h>

#include <algorithm>

namespace lamina::micro::detail {

namespace {

std::string datasetOf(const ImageSource& src) {
  return src.dataset.empty() ? "/phases" : src.dataset;
}

herr_t collect(hid_t, const char* name, const H5O_info_t* info, void* out) {
  if (info->type == H5O_TYPE_DATASET)
    static_cast<std::vector<std::string>*>(out)->push_back(std::string("/") + name);
  return 0;
}

/// The open dataset of @p src, its dimensions in file order and its type.
struct OpenDataset {
  core::H5Handle file, set, type;
  std::vector<hsize_t> dims;
  std::uint64_t bytes = 0; ///< size of the file
};

OpenDataset open(const ImageSource& src) {
  OpenDataset d;
  d.bytes = openImage(src).size(); // a regular file: HDF5 would block on a FIFO
  d.file = core::H5Handle(H5Fopen(src.path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (d.file.id() < 0) {
    const std::string reason = core::hdf5TruncationReason();
    imageError(src, reason.empty() ? "not an HDF5 file (or unreadable)"
                                   : "truncated HDF5 file: " + reason);
  }
  const std::string name = datasetOf(src);
  const htri_t ok = H5Lexists(d.file.id(), name.c_str(), H5P_DEFAULT);
  if (ok > 0)
    d.set = core::H5Handle(H5Dopen2(d.file.id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (ok <= 0 || d.set.id() < 0) {
    std::vector<std::string> sets;
    H5Ovisit2(d.file.id(), H5_INDEX_NAME, H5_ITER_NATIVE, collect, &sets, H5O_INFO_BASIC);
    std::string list;
    for (const auto& s : sets)
      list += (list.empty() ? "" : ", ") + s;
    throw Error("no dataset '" + name + "' in " + src.path.string() +
                    " (it holds: " + (list.empty() ? "no datasets" : list) + ")",
                {src.cell_file, 0, "cell.dataset"});
  }
  d.type = core::H5Handle(H5Dget_type(d.set.id()), H5Tclose);
  if (H5Tget_class(d.type.id()) != H5T_INTEGER)
    throw Error("dataset '" + name + "' in " + src.path.string() +
                    " must hold integer labels (phase ids), not floating point or other data",
                {src.cell_file, 0, "cell.dataset"});
  core::H5Handle space(H5Dget_space(d.set.id()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.id());
  if (rank != 3)
    throw Error("dataset '" + name + "' in " + src.path.string() + " has rank " +
                    std::to_string(rank) + "; a voxel image needs 3 dimensions",
                {src.cell_file, 0, "cell.dataset"});
  d.dims.resize(3);
  H5Sget_simple_extent_dims(space.id(), d.dims.data(), nullptr);
  return d;
}

std::array<int, 3> xyzDims(const OpenDataset& d, const ImageSource& src) {
  std::array<int, 3> n{};
  for (std::size_t a = 0; a < 3; ++a) {
    const hsize_t m = d.dims[src.axes == AxisOrder::Xyz ? a : 2 - a];
    if (m < 1 || m > 1000000000)
      imageError(src, "dataset '" + datasetOf(src) + "' has " + std::to_string(m) +
                          " voxels along " + std::string(1, "xyz"[a]) + " (1 to 1e9 accepted)");
    n[a] = static_cast<int>(m);
  }
  return n;
}

/// Checks that the file holds every label the dataset's dimensions name:
/// contiguous data whole and inside the file, every chunk of chunked data
/// written (an unwritten chunk would read as fill values).
void checkStorage(const OpenDataset& d, const ImageSource& src, std::size_t voxels) {
  const std::string name = "dataset '" + datasetOf(src) + "'";
  core::H5Handle dcpl(H5Dget_create_plist(d.set.id()), H5Pclose);
  const H5D_layout_t layout = H5Pget_layout(dcpl.id());
  const std::uint64_t need = voxels * H5Tget_size(d.type.id());
  if (layout == H5D_CONTIGUOUS) {
    const hsize_t stored = H5Dget_storage_size(d.set.id());
    const haddr_t at = H5Dget_offset(d.set.id());
    if (stored < need || at == HADDR_UNDEF || at > d.bytes || need > d.bytes - at)
      imageError(src, "truncated HDF5 file: " + name + " needs " + std::to_string(need) +
                          " bytes of labels, the file holds " +
                          (at == HADDR_UNDEF ? std::string("none written")
                                             : std::to_string(std::min<std::uint64_t>(
                                                   stored, d.bytes - std::min(d.bytes, at)))));
  } else if (layout == H5D_CHUNKED) {
    hsize_t chunk[3] = {1, 1, 1}, chunks = 0;
    H5Pget_chunk(dcpl.id(), 3, chunk);
    hsize_t expected = 1;
    for (std::size_t a = 0; a < 3; ++a)
      expected *= (d.dims[a] + std::max<hsize_t>(chunk[a], 1) - 1) / std::max<hsize_t>(chunk[a], 1);
    core::H5Handle space(H5Dget_space(d.set.id()), H5Sclose);
    if (H5Dget_num_chunks(d.set.id(), space.id(), &chunks) < 0 || chunks < expected)
      imageError(src, "truncated HDF5 file: " + name + " stores " + std::to_string(chunks) +
                          " of its " + std::to_string(expected) +
                          " chunks (the rest would read as fill values)");
  }
}

std::optional<double> doubleAttribute(hid_t set, const char* name) {
  if (H5Aexists(set, name) <= 0)
    return std::nullopt;
  core::H5Handle a(H5Aopen(set, name, H5P_DEFAULT), H5Aclose);
  double v = 0;
  if (a.id() < 0 || H5Aread(a.id(), H5T_NATIVE_DOUBLE, &v) < 0)
    return std::nullopt;
  return v;
}

} // namespace

std::array<int, 3> probeHdf5Image(const ImageSource& src) {
  const OpenDataset d = open(src);
  return xyzDims(d, src);
}

VoxelImage readHdf5Image(const ImageSource& src) {
  const OpenDataset d = open(src);
  VoxelImage img;
  img.n = xyzDims(d, src);
  checkImageMemory(src, img.voxels(), 4);
  checkStorage(d, src, img.voxels());
  std::vector<std::int32_t> raw(img.voxels());
  // HDF5 converts any integer type and byte order to native int32
  core::H5Handle xfer(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  if (H5Dread(d.set.id(), H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, xfer.id(), raw.data()) < 0)
    imageError(src, "cannot read dataset '" + datasetOf(src) +
                        "' (truncated or corrupt file, or labels beyond 32 bits)");
  img.value = toXSlowest(std::move(raw), img.n, src.axes);
  // voxel size: lamina's own size_x/y/z (edge lengths of the cell)
  const auto sx = doubleAttribute(d.set.id(), "size_x"), sy = doubleAttribute(d.set.id(), "size_y"),
             sz = doubleAttribute(d.set.id(), "size_z");
  if (sx && sy && sz)
    img.spacing = Eigen::Vector3d(*sx / img.n[0], *sy / img.n[1], *sz / img.n[2]);
  return img;
}

void writeHdf5Image(const VoxelImage& image, const std::filesystem::path& path,
                    const ImageWriteOptions& options) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    core::H5File f(tmp, core::H5File::Mode::Create);
    const std::string name = "/" + options.name;
    f.writeInts(name, image.value.data(),
                {static_cast<std::uint64_t>(image.n[0]), static_cast<std::uint64_t>(image.n[1]),
                 static_cast<std::uint64_t>(image.n[2])});
    const Eigen::Vector3d h = image.spacing.value_or(Eigen::Vector3d::Ones());
    f.writeAttribute(name, "size_x", h[0] * image.n[0]);
    f.writeAttribute(name, "size_y", h[1] * image.n[1]);
    f.writeAttribute(name, "size_z", h[2] * image.n[2]);
    f.writeAttribute(name, "layout", std::string("C order, x slowest: index (i*N2+j)*N3+k"));
  }
  core::renameIntoPlace(tmp, path);
}

} // namespace lamina::micro::detail
