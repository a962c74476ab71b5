#include "membrane/io/output.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>

namespace lamina::membrane {

void removeTemporaries(const std::filesystem::path& dir, const std::vector<std::string>& files) {
  std::error_code ec;
  std::vector<std::filesystem::path> debris;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    for (const auto& f : files)
      if (name.rfind(core::temporaryPrefix(dir / f), 0) == 0)
        debris.push_back(entry.path());
  }
  for (const auto& p : debris)
    std::filesystem::remove(p, ec);
}

FieldWriter::FieldWriter(const std::filesystem::path& dir, const std::string& stem,
                         const Mesh& mesh, bool deformed_geometry)
    : h5_path_(dir / (stem + ".h5")), xdmf_path_(dir / (stem + ".xdmf")), mesh_(mesh),
      deformed_(deformed_geometry) {
  file_ = std::make_unique<core::H5File>(h5_path_, core::H5File::Mode::Create);
  const auto n = static_cast<std::uint64_t>(mesh.numNodes());
  const auto ne = static_cast<std::uint64_t>(mesh.numElements());
  std::vector<double> xyz(3 * n, 0.0);
  for (std::uint64_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = mesh.point(static_cast<int>(i));
    for (int c = 0; c < 3; ++c)
      xyz[3 * i + c] = p[c];
  }
  std::vector<std::int32_t> tri(3 * ne), region(ne);
  for (std::uint64_t e = 0; e < ne; ++e) {
    for (int k = 0; k < 3; ++k)
      tri[3 * e + k] = mesh.triangles[e][k];
    region[e] = mesh.region_of[e];
  }
  file_->createGroup("/mesh");
  file_->writeDoubles("/mesh/geometry", xyz.data(), {n, 3});
  file_->writeInts("/mesh/topology", tri.data(), {ne, 3});
  file_->writeInts("/mesh/region", region.data(), {ne});
  // The user's numbers of the nodes and triangles (gmsh tags; indices for the
  // rectangle): a run renumbers gmsh meshes for speed (mesh_ordering.hpp).
  std::vector<std::uint64_t> node_id(n), element_id(ne);
  for (std::uint64_t i = 0; i < n; ++i)
    node_id[i] = mesh.nodeLabel(static_cast<int>(i));
  for (std::uint64_t e = 0; e < ne; ++e)
    element_id[e] = mesh.elementLabel(static_cast<int>(e));
  file_->writeUInt64s("/mesh/node_id", node_id.data(), {n});
  file_->writeUInt64s("/mesh/element_id", element_id.data(), {ne});
  file_->createGroup("/steps");
  file_->flush();
  writeIndex();
}

FieldWriter::FieldWriter(const std::filesystem::path& dir, const std::string& stem,
                         const Mesh& mesh, bool deformed_geometry, const std::vector<double>& times,
                         const std::vector<CellField>& cells)
    : h5_path_(dir / (stem + ".h5")), xdmf_path_(dir / (stem + ".xdmf")), mesh_(mesh),
      deformed_(deformed_geometry), times_(times) {
  if (!std::filesystem::is_regular_file(h5_path_))
    throw Error("cannot continue the field series: the file is missing",
                {h5_path_.string(), 0, ""});
  file_ = std::make_unique<core::H5File>(h5_path_, core::H5File::Mode::ReadWrite);
  for (std::size_t k = 0; k < times_.size(); ++k) // the steps the checkpoint counts are all there
    if (!file_->exists("/steps/" + std::to_string(k) + "/displacement"))
      throw Error("cannot continue the field series: the checkpoint counts " +
                      std::to_string(times_.size()) + " steps, step " + std::to_string(k) +
                      " is missing",
                  {h5_path_.string(), 0, ""});
  // Steps written after the checkpoint (a crash or kill between two
  // checkpoints) are removed: the continued series holds only what an
  // uninterrupted run writes, even if this run ends before rewriting them.
  for (std::size_t k = times_.size(); file_->exists("/steps/" + std::to_string(k)); ++k)
    file_->remove("/steps/" + std::to_string(k));
  file_->flush();
  for (const auto& c : cells)
    cells_.emplace_back(c.name, c.components);
  writeIndex();
}

void FieldWriter::write(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                        const std::vector<CellField>& cells) {
  const auto n = static_cast<std::uint64_t>(mesh_.numNodes());
  const auto ne = static_cast<std::uint64_t>(mesh_.numElements());
  const std::string g = "/steps/" + std::to_string(times_.size());
  file_->createGroup(g);
  file_->writeDoubles(g + "/displacement", u.data(), {n, 3});
  file_->writeDoubles(g + "/velocity", v.data(), {n, 3});
  std::vector<double> speed(n);
  for (std::uint64_t i = 0; i < n; ++i)
    speed[i] = v.segment<3>(3 * i).norm();
  file_->writeDoubles(g + "/speed", speed.data(), {n});
  if (deformed_) {
    std::vector<double> xyz(3 * n);
    for (std::uint64_t i = 0; i < n; ++i) {
      const Eigen::Vector3d x = mesh_.point(static_cast<int>(i)) + u.segment<3>(3 * i);
      for (int c = 0; c < 3; ++c)
        xyz[3 * i + c] = x[c];
    }
    file_->writeDoubles(g + "/geometry", xyz.data(), {n, 3});
  }
  cells_.clear();
  for (const auto& c : cells) {
    const auto k = static_cast<std::uint64_t>(c.components);
    if (k == 1)
      file_->writeDoubles(g + "/" + c.name, c.values.data(), {ne});
    else
      file_->writeDoubles(g + "/" + c.name, c.values.data(), {ne, k});
    cells_.emplace_back(c.name, c.components);
  }
  file_->writeAttribute(g, "time", t);
  file_->flush();
  times_.push_back(t);
  writeIndex();
}

void FieldWriter::writeIndex() const {
  const auto n = mesh_.numNodes();
  const auto ne = mesh_.numElements();
  const std::string h5 = core::xmlEscape(h5_path_.filename().string());
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"membrane\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  auto attr = [&](const std::string& name, const std::string& center, const std::string& type,
                  int rows, int cols, const std::string& path) {
    x << "    <Attribute Name=\"" << name << "\" AttributeType=\"" << type << "\" Center=\""
      << center << "\">\n      <DataItem Dimensions=\"" << rows;
    if (cols > 1)
      x << " " << cols;
    x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":" << path
      << "</DataItem>\n    </Attribute>\n";
  };
  for (size_t s = 0; s < times_.size(); ++s) {
    const std::string g = "/steps/" + std::to_string(s);
    x << "   <Grid Name=\"step" << s << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << core::formatExact(times_[s]) << "\"/>\n"
      << "    <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << ne
      << "\">\n     <DataItem Dimensions=\"" << ne
      << " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5
      << ":/mesh/topology</DataItem>\n    </Topology>\n"
      << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" << n
      << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":"
      << (deformed_ ? g + "/geometry" : std::string("/mesh/geometry"))
      << "</DataItem>\n    </Geometry>\n";
    attr("displacement", "Node", "Vector", n, 3, g + "/displacement");
    attr("velocity", "Node", "Vector", n, 3, g + "/velocity");
    attr("speed", "Node", "Scalar", n, 1, g + "/speed");
    for (const auto& [name, k] : cells_)
      attr(name, "Cell", k == 1 ? "Scalar" : "Matrix", ne, k, g + "/" + name);
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  core::writeFileAtomically(xdmf_path_, x.str());
}

namespace {
/// @return @p part once core::checkReplaceable() accepts it (a FIFO standing
/// where a table is written blocked the run in its open; a device was written)
std::string replaceablePart(const std::filesystem::path& part) {
  core::checkReplaceable(part);
  return part.string();
}
} // namespace

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::string& header)
    : path_(path), out_(replaceablePart(path.string() + ".part")) {
  if (!out_)
    throw Error("cannot write", ErrorContext{path.string() + ".part", 0, ""});
  out_ << header << '\n';
  bytes_ = header.size() + 1;
}

namespace {
/// Throws (naming @p where) unless the first @p bytes of file @p part end a
/// line and hold exactly @p lines lines.
void checkLines(const std::filesystem::path& part, std::uintmax_t bytes, std::uintmax_t lines,
                const ErrorContext& where) {
  std::ifstream in(part, std::ios::binary);
  std::uintmax_t seen = 0, left = bytes;
  char last = '\n';
  std::vector<char> buf(1 << 16);
  while (left > 0 && in) {
    in.read(buf.data(), static_cast<std::streamsize>(std::min<std::uintmax_t>(left, buf.size())));
    const auto got = static_cast<std::size_t>(in.gcount());
    seen += static_cast<std::uintmax_t>(std::count(buf.data(), buf.data() + got, '\n'));
    if (got > 0)
      last = buf[got - 1];
    left -= got;
  }
  if (left > 0 || last != '\n' || seen != lines)
    throw Error("cannot continue the table: the checkpoint's " + std::to_string(bytes) +
                    " bytes hold " + std::to_string(seen) + " lines" +
                    (last != '\n' ? " and end inside a row" : "") + ", its step needs " +
                    std::to_string(lines) + " (the header and " + std::to_string(lines - 1) +
                    " rows)",
                where);
}
} // namespace

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::string& header,
                     std::uintmax_t bytes, std::uintmax_t rows)
    : path_(path), bytes_(bytes) {
  const std::filesystem::path part = path.string() + ".part";
  if (!std::filesystem::exists(part)) {
    if (!std::filesystem::exists(path))
      throw Error("cannot continue the table: neither it nor its .part file exists",
                  ErrorContext{path.string(), 0, ""});
    core::renameIntoPlace(path, part);
  }
  const ErrorContext where{part.string(), 0, ""};
  std::string first;
  {
    // the run's own table: a regular file, of any size (only its first line
    // and the checkpoint's byte count are read)
    core::checkRegularInput(part, "table being continued",
                            std::numeric_limits<std::uintmax_t>::max());
    std::ifstream in(part);
    std::getline(in, first);
  }
  if (first != header)
    throw Error("cannot continue the table: its header is not this run's", where);
  const std::uintmax_t size = std::filesystem::file_size(part);
  if (size < bytes)
    throw Error("cannot continue the table: it holds " + std::to_string(size) +
                    " bytes, the checkpoint expects " + std::to_string(bytes),
                where);
  checkLines(part, bytes, rows + 1, where);
  std::filesystem::resize_file(part, bytes);
  out_.open(part, std::ios::app);
  if (!out_)
    throw Error("cannot write", where);
}

void CsvWriter::row(const std::vector<double>& values) {
  std::string line;
  for (size_t k = 0; k < values.size(); ++k) {
    if (k)
      line += ',';
    line += core::formatExact(values[k]);
  }
  line += '\n';
  out_ << line;
  out_.flush();
  bytes_ += line.size();
}

void CsvWriter::close() {
  if (closed_)
    return;
  out_.close();
  core::renameIntoPlace(path_.string() + ".part", path_);
  closed_ = true;
}

} // namespace lamina::membrane
