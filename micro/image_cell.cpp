#include "micro/image_cell.hpp"

#include "core/error.hpp"

#include <map>
#include <unordered_map>

namespace lamina::micro {

std::vector<std::int32_t> phaseLabels(const CellSpec& spec) {
  std::vector<std::int32_t> out;
  for (std::size_t p = 0; p < spec.phases.size(); ++p)
    out.push_back(spec.phases[p].id ? *spec.phases[p].id : static_cast<std::int32_t>(p));
  return out;
}

UnitCell buildImageCell(const CellSpec& spec) {
  LAMINA_CHECK(spec.image.has_value(), "not an image cell");
  const ImageSource& src = *spec.image;
  VoxelImage img = readImage(src);
  UnitCell cell;
  cell.n = img.n;
  cell.phase_count = static_cast<int>(spec.phases.size());
  if (spec.voxel_size)
    cell.size = spec.voxel_size->cwiseProduct(Eigen::Vector3d(img.n[0], img.n[1], img.n[2]));
  else if (spec.physical_size)
    cell.size = spec.size;
  else if (img.spacing)
    cell.size = img.spacing->cwiseProduct(Eigen::Vector3d(img.n[0], img.n[1], img.n[2]));
  else
    cell.size = Eigen::Vector3d(img.n[0], img.n[1], img.n[2]);
  std::unordered_map<std::int32_t, std::int32_t> phase_of;
  const auto labels = phaseLabels(spec);
  for (std::size_t p = 0; p < labels.size(); ++p)
    phase_of[labels[p]] = static_cast<std::int32_t>(p);
  std::map<std::int32_t, std::size_t> orphans;
  std::vector<std::int32_t>& phase = cell.phase.values();
  phase.resize(img.voxels());
  for (std::size_t v = 0; v < img.voxels(); ++v) {
    const auto it = phase_of.find(img.value[v]);
    if (it == phase_of.end())
      ++orphans[img.value[v]];
    else
      phase[v] = it->second;
  }
  if (!orphans.empty()) {
    std::string list, owned;
    for (const auto& [label, count] : orphans)
      list += (list.empty() ? "" : ", ") + std::to_string(label) + " (" + std::to_string(count) +
              " voxels)";
    for (std::size_t p = 0; p < labels.size(); ++p)
      owned +=
          (owned.empty() ? "" : ", ") + spec.phases[p].name + " = " + std::to_string(labels[p]);
    throw Error("image " + src.path.string() + " holds values no phase owns: " + list +
                    "; give each a [[phases]] table with id = VALUE (ids now: " + owned + ")",
                {spec.file, 0, "phases"});
  }
  cell.countFractions();
  return cell;
}

VoxelImage labelImage(const CellSpec& spec, const UnitCell& cell) {
  VoxelImage img;
  img.n = cell.n;
  img.spacing = cell.size.cwiseQuotient(Eigen::Vector3d(cell.n[0], cell.n[1], cell.n[2]));
  const auto labels = phaseLabels(spec);
  img.value.resize(cell.voxels());
  for (std::size_t v = 0; v < cell.voxels(); ++v)
    img.value[v] = labels[static_cast<std::size_t>(cell.phase[v])];
  return img;
}

} // namespace lamina::micro
