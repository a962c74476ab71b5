// HDF5 voxel images: an integer dataset of rank 3 (see image_formats.hpp).

#include "core/atomic_file.hpp"
#include "core/hdf5_file.hpp"
#include "micro/image_formats.hpp"

#include <hdf5.h>

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
};

OpenDataset open(const ImageSource& src) {
  OpenDataset d;
  d.file = core::H5Handle(H5Fopen(src.path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (d.file.id() < 0)
    imageError(src, "not an HDF5 file (or unreadable)");
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
  for (std::size_t a = 0; a < 3; ++a)
    n[a] = static_cast<int>(d.dims[src.axes == AxisOrder::Xyz ? a : 2 - a]);
  return n;
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
