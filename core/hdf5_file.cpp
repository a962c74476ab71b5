#include "core/hdf5_file.hpp"

#include "core/atomic_file.hpp"

#include "core/error.hpp"
#include "core/input_file.hpp"

#include <exception>
#include <limits>

namespace lamina::core {

H5Handle& H5Handle::operator=(H5Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    closer_ = o.closer_;
    o.id_ = -1;
  }
  return *this;
}

void H5Handle::reset() {
  if (id_ >= 0 && closer_)
    closer_(id_);
  id_ = -1;
}

namespace {
struct SilenceHdf5 {
  SilenceHdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
};
const SilenceHdf5 silence_hdf5_stack_dumps; // errors are reported as lamina::Error
} // namespace

namespace {
herr_t findTruncation(unsigned, const H5E_error2_t* e, void* out) {
  if (e->desc && std::string(e->desc).find("truncated file") != std::string::npos)
    *static_cast<std::string*>(out) = e->desc;
  return 0;
}
} // namespace

std::string hdf5TruncationReason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, findTruncation, &reason);
  return reason;
}

H5File::H5File(const std::filesystem::path& path, Mode mode, std::uint64_t userblock)
    : path_(path) {
  hid_t id = -1;
  if (mode != Mode::Create) // HDF5 would block on a FIFO and read a device
    checkRegularInput(path, "HDF5 file", kMaxHdf5Bytes);
  else // and truncate a device, or block on a FIFO, that stands where it creates
    checkReplaceable(path);
  switch (mode) {
  case Mode::Create:
    if (userblock > 0) {
      const H5Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
      if (fcpl.id() < 0 || H5Pset_userblock(fcpl.id(), userblock) < 0)
        fail("cannot set a user block of " + std::to_string(userblock) + " bytes", "/");
      id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.id(), H5P_DEFAULT);
    } else {
      id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    }
    break;
  case Mode::ReadOnly:
    id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    break;
  case Mode::ReadWrite:
    id = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    break;
  }
  if (id < 0) {
    const std::string reason = hdf5TruncationReason();
    fail(std::string(mode == Mode::Create ? "cannot create HDF5 file" : "cannot open HDF5 file") +
             (reason.empty() ? "" : " (" + reason + ")"),
         "");
  }
  file_ = H5Handle(id, H5Fclose);
}

void H5File::fail(const std::string& what, const std::string& object) const {
  throw Error(what, {path_.string(), 0, object});
}

bool H5File::exists(const std::string& name) const {
  if (name == "/")
    return true;
  // Check each prefix: H5Lexists fails on a missing intermediate group.
  std::size_t pos = 0;
  while (true) {
    pos = name.find('/', pos + 1);
    const std::string prefix = name.substr(0, pos);
    if (!prefix.empty() && prefix != "/" && H5Lexists(file_.id(), prefix.c_str(), H5P_DEFAULT) <= 0)
      return false;
    if (pos == std::string::npos)
      return true;
  }
}

void H5File::remove(const std::string& name) {
  if (exists(name) && H5Ldelete(file_.id(), name.c_str(), H5P_DEFAULT) < 0)
    fail("cannot remove", name);
}

void H5File::createGroup(const std::string& name) {
  if (exists(name))
    return;
  H5Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.id(), 1);
  const hid_t g = H5Gcreate2(file_.id(), name.c_str(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0)
    fail("cannot create group", name);
  H5Gclose(g);
}

void H5File::write(const std::string& name, hid_t type, const void* data,
                   const std::vector<std::uint64_t>& dims) {
  std::vector<hsize_t> d(dims.begin(), dims.end());
  H5Handle space(H5Screate_simple(static_cast<int>(d.size()), d.data(), nullptr), H5Sclose);
  if (space.id() < 0)
    fail("cannot create dataspace", name);
  H5Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.id(), 1);
  if (exists(name))
    H5Ldelete(file_.id(), name.c_str(), H5P_DEFAULT);
  H5Handle set(
      H5Dcreate2(file_.id(), name.c_str(), type, space.id(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (set.id() < 0)
    fail("cannot create dataset", name);
  if (H5Dwrite(set.id(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail("cannot write dataset", name);
}

void H5File::writeDoubles(const std::string& name, const double* data,
                          const std::vector<std::uint64_t>& dims) {
  write(name, H5T_NATIVE_DOUBLE, data, dims);
}

void H5File::writeInts(const std::string& name, const std::int32_t* data,
                       const std::vector<std::uint64_t>& dims) {
  write(name, H5T_NATIVE_INT32, data, dims);
}

void H5File::writeUInt64s(const std::string& name, const std::uint64_t* data,
                          const std::vector<std::uint64_t>& dims) {
  write(name, H5T_NATIVE_UINT64, data, dims);
}

namespace {
/// @return the number of values of dataset @p set of shape @p d whose type
/// has @p bytes bytes; throws naming the dataset when they cannot be there:
/// the product overflows, or (no filters, so the values are stored as they
/// are) they need more bytes than the file holds for the dataset. A
/// corrupted shape would otherwise allocate without bound before reading.
std::size_t storedValues(hid_t set, const std::vector<hsize_t>& d, std::size_t bytes,
                         const H5File& self, const std::string& name) {
  const ErrorContext where{self.path().string(), 0, name};
  std::size_t n = 1;
  for (hsize_t x : d) {
    if (x != 0 && n > std::numeric_limits<std::size_t>::max() / 8 / x)
      throw Error("dataset shape is too large", where);
    n *= x;
  }
  H5Handle plist(H5Dget_create_plist(set), H5Pclose);
  if (plist.id() >= 0 && H5Pget_nfilters(plist.id()) == 0 && n * bytes > H5Dget_storage_size(set))
    throw Error("dataset holds fewer bytes than its shape needs (" +
                    std::to_string(H5Dget_storage_size(set)) + " of " + std::to_string(n * bytes) +
                    ")",
                where);
  return n;
}

template <typename T>
std::vector<T> readAll(hid_t file, const std::string& name, hid_t type,
                       std::vector<std::uint64_t>& dims, const H5File& self) {
  H5Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.id() < 0)
    throw Error("no such dataset", {self.path().string(), 0, name});
  H5Handle space(H5Dget_space(set.id()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.id());
  std::vector<hsize_t> d(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.id(), d.data(), nullptr);
  dims.assign(d.begin(), d.end());
  // The stored type must be a number of the kind asked for, of at most 8
  // bytes: a corrupted size (4 GB per value) made H5Dread allocate that much.
  H5Handle stored(H5Dget_type(set.id()), H5Tclose);
  if (stored.id() < 0 || H5Tget_class(stored.id()) != H5Tget_class(type) ||
      H5Tget_size(stored.id()) > 8)
    throw Error("dataset does not hold numbers of the expected kind (at most 8 bytes each)",
                {self.path().string(), 0, name});
  const std::size_t n = storedValues(set.id(), d, H5Tget_size(stored.id()), self, name);
  std::vector<T> out;
  try { // a filtered (compressed) dataset may still claim more than memory holds
    out.resize(n);
  } catch (const std::exception&) { // std::bad_alloc, std::length_error
    throw Error("dataset of " + std::to_string(n) + " values does not fit in memory",
                {self.path().string(), 0, name});
  }
  if (n > 0 && H5Dread(set.id(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw Error("cannot read dataset", {self.path().string(), 0, name});
  return out;
}
} // namespace

std::vector<double> H5File::readDoubles(const std::string& name,
                                        std::vector<std::uint64_t>& dims) const {
  return readAll<double>(file_.id(), name, H5T_NATIVE_DOUBLE, dims, *this);
}

std::vector<std::int32_t> H5File::readInts(const std::string& name,
                                           std::vector<std::uint64_t>& dims) const {
  return readAll<std::int32_t>(file_.id(), name, H5T_NATIVE_INT32, dims, *this);
}

void H5File::writeAttribute(const std::string& object, const std::string& attr,
                            const std::string& value) {
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id(), value.size() + 1);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists_by_name(file_.id(), object.c_str(), attr.c_str(), H5P_DEFAULT) > 0)
    H5Adelete_by_name(file_.id(), object.c_str(), attr.c_str(), H5P_DEFAULT);
  H5Handle a(H5Acreate_by_name(file_.id(), object.c_str(), attr.c_str(), type.id(), space.id(),
                               H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Aclose);
  if (a.id() < 0 || H5Awrite(a.id(), type.id(), value.c_str()) < 0)
    fail("cannot write attribute " + attr, object);
}

void H5File::writeAttribute(const std::string& object, const std::string& attr, double value) {
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists_by_name(file_.id(), object.c_str(), attr.c_str(), H5P_DEFAULT) > 0)
    H5Adelete_by_name(file_.id(), object.c_str(), attr.c_str(), H5P_DEFAULT);
  H5Handle a(H5Acreate_by_name(file_.id(), object.c_str(), attr.c_str(), H5T_NATIVE_DOUBLE,
                               space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Aclose);
  if (a.id() < 0 || H5Awrite(a.id(), H5T_NATIVE_DOUBLE, &value) < 0)
    fail("cannot write attribute " + attr, object);
}

std::string H5File::readStringAttribute(const std::string& object, const std::string& attr) const {
  H5Handle a(H5Aopen_by_name(file_.id(), object.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT),
             H5Aclose);
  if (a.id() < 0)
    fail("no attribute " + attr, object);
  H5Handle type(H5Aget_type(a.id()), H5Tclose);
  const std::size_t size = H5Tget_size(type.id());
  std::string out(size, '\0');
  H5Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem.id(), size);
  if (H5Aread(a.id(), mem.id(), out.data()) < 0)
    fail("cannot read attribute " + attr, object);
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

void H5File::flush() {
  H5Fflush(file_.id(), H5F_SCOPE_GLOBAL);
}

} // namespace lamina::core
