#include "micro/phase_map_io.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/hdf5_file.hpp"

#include <sstream>

namespace lamina::micro {

void writePhaseMap(const UnitCell& cell, const std::vector<std::string>& phase_names,
                   const std::filesystem::path& h5) {
  const std::filesystem::path tmp = h5.string() + ".tmp";
  {
    core::H5File f(tmp, core::H5File::Mode::Create);
    f.writeInts("/phases", cell.phase.data(),
                {static_cast<std::uint64_t>(cell.n[0]), static_cast<std::uint64_t>(cell.n[1]),
                 static_cast<std::uint64_t>(cell.n[2])});
    f.writeAttribute("/phases", "size_x", cell.size[0]);
    f.writeAttribute("/phases", "size_y", cell.size[1]);
    f.writeAttribute("/phases", "size_z", cell.size[2]);
    std::string names;
    for (std::size_t i = 0; i < phase_names.size(); ++i)
      names += (i ? "," : "") + phase_names[i];
    f.writeAttribute("/phases", "phase_names", names);
    f.writeAttribute("/phases", "layout", std::string("C order, x slowest: index (i*N2+j)*N3+k"));
  }
  core::renameIntoPlace(tmp, h5);

  // XDMF: a 3DCoRectMesh of (N+1)^3 nodes with the phase as a cell attribute.
  // Dimensions and spacing are listed slowest first (x, y, z here), so
  // ParaView's Z axis is the cell's x axis.
  std::ostringstream x;
  const Eigen::Vector3d h(cell.size[0] / cell.n[0], cell.size[1] / cell.n[1],
                          cell.size[2] / cell.n[2]);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\"cell\" "
       "GridType=\"Uniform\">\n   <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\""
    << cell.n[0] + 1 << " " << cell.n[1] + 1 << " " << cell.n[2] + 1
    << "\"/>\n   <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n    <DataItem Dimensions=\"3\" "
       "Format=\"XML\">0 0 0</DataItem>\n    <DataItem Dimensions=\"3\" Format=\"XML\">"
    << core::formatExact(h[0]) << " " << core::formatExact(h[1]) << " " << core::formatExact(h[2])
    << "</DataItem>\n   </Geometry>\n   <Attribute Name=\"phase\" Center=\"Cell\" "
       "AttributeType=\"Scalar\">\n    <DataItem Dimensions=\""
    << cell.n[0] << " " << cell.n[1] << " " << cell.n[2]
    << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
    << core::xmlEscape(h5.filename().string())
    << ":/phases</DataItem>\n   </Attribute>\n  </Grid>\n </Domain>\n</Xdmf>\n";
  std::filesystem::path xdmf = h5;
  xdmf.replace_extension(".xdmf");
  core::writeFileAtomically(xdmf, x.str());
}

UnitCell readPhaseMap(const std::filesystem::path& h5, int phase_count) {
  core::H5File f(h5, core::H5File::Mode::ReadOnly);
  std::vector<std::uint64_t> dims;
  UnitCell cell;
  cell.phase = f.readInts("/phases", dims);
  if (dims.size() != 3)
    throw Error("dataset /phases must be 3-dimensional", {h5.string(), 0, "/phases"});
  for (int d = 0; d < 3; ++d)
    cell.n[static_cast<std::size_t>(d)] = static_cast<int>(dims[static_cast<std::size_t>(d)]);
  cell.phase_count = phase_count;
  for (std::int32_t p : cell.phase)
    if (p < 0 || p >= phase_count)
      throw Error("phase index " + std::to_string(p) + " outside [0, " +
                      std::to_string(phase_count) + ")",
                  {h5.string(), 0, "/phases"});
  cell.countFractions();
  return cell;
}

} // namespace lamina::micro
