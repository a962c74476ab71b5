/// @file cell.cpp
/// @brief Python bindings: lamina.Cell (python/lamina/__init__.pyi), see
/// cell.hpp. A cell file is read and built as `homogenize CELL` does
/// (micro::readCell, micro::buildCell); a cell from a numpy label array has
/// its phases read by the same reader, from a cell document made of the
/// phases dict, and its phase map borrows the array when it can
/// (int32, C order, ids 0..P-1) or is one copy of it.
#include "python/src/cell.hpp"

#include "core/checksum.hpp"
#include "core/error.hpp"
#include "micro/unit_cell.hpp"
#include "python/src/convert.hpp"

#include <pybind11/numpy.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

namespace lamina::python {

namespace {

/// The source name of an array cell in messages and provenance.
constexpr const char* kArraySource = "<array>";

/// @return the catalog provider of @p catalog (None: --catalog's default)
micro::CatalogProvider catalogOf(py::handle catalog) {
  return micro::lazyCatalog(catalog.is_none()
                                ? std::filesystem::path()
                                : std::filesystem::path(pathArgument(catalog, "catalog")));
}

std::shared_ptr<CellData> fromFile(hint::Path path, hint::Overrides set,
                                   hint::OptionalPath catalog) {
  auto data = std::make_shared<CellData>();
  data->source = requiredPath(path, "path");
  const std::vector<std::string> overrides = toOverrides(set);
  const micro::CatalogProvider provider = catalogOf(catalog);
  py::gil_scoped_release release; // reading and voxelizing touch no Python object
  data->spec = micro::readCell(data->source, provider, overrides);
  data->cell = micro::buildCell(data->spec, data->spec.resolution);
  return data;
}

// ---------------------------------------------------------------- from_array

/// The label array as numpy sees it: its memory, shape and byte strides.
struct Labels {
  py::array array;                     ///< the array (kept alive while read)
  const char* base = nullptr;          ///< its first element
  std::array<py::ssize_t, 3> n{};      ///< shape: x, y, z
  std::array<py::ssize_t, 3> stride{}; ///< byte strides (may be negative)
  char kind = 'i';                     ///< 'i' signed, 'u' unsigned
  int itemsize = 4;                    ///< bytes per label
  bool converted = false;              ///< not the caller's array (np.asarray made it)

  std::size_t voxels() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
           static_cast<std::size_t>(n[2]);
  }
};

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// @return @p labels as a checked 3D integer array in native byte order
Labels labelsOf(py::handle labels) {
  Labels l;
  if (py::isinstance<py::array>(labels)) {
    l.array = py::reinterpret_borrow<py::array>(labels);
  } else {
    try { // nested lists of integers are fine
      l.array = py::module_::import("numpy").attr("asarray")(labels);
    } catch (py::error_already_set& e) {
      throwInput("labels must be a 3D integer array (numpy array or nested lists), got " +
                     typeName(labels) + " (" + e.what() + ")",
                 "labels");
    }
    l.converted = true;
  }
  const py::array& a = l.array;
  if (a.ndim() != 3)
    throwInput("labels must be 3-dimensional (axis 0 = x, 1 = y, 2 = z), got " +
                   std::to_string(a.ndim()) + " dimension(s) of shape " + shapeText(a),
               "labels");
  if (a.size() == 0)
    throwInput("labels is empty (shape " + shapeText(a) + ")", "labels");
  l.kind = a.dtype().kind();
  if (l.kind != 'i' && l.kind != 'u')
    throwInput("labels must hold integers (any integer dtype), got dtype " +
                   std::string(py::str(a.dtype())),
               "labels");
  for (int d = 0; d < 3; ++d)
    if (a.shape(d) < 2 || a.shape(d) > micro::kMaxResolution)
      throwInput("each axis of labels must have 2 to " + std::to_string(micro::kMaxResolution) +
                     " voxels (a cell file's resolution), got shape " + shapeText(a),
                 "labels");
  if (!a.dtype().attr("isnative").cast<bool>()) { // byte-swapped: one conversion first
    l.array = a.attr("astype")(a.dtype().attr("newbyteorder")("="));
    l.converted = true;
  }
  l.base = static_cast<const char*>(l.array.data());
  l.itemsize = static_cast<int>(l.array.itemsize());
  for (int d = 0; d < 3; ++d) {
    l.n[static_cast<std::size_t>(d)] = l.array.shape(d);
    l.stride[static_cast<std::size_t>(d)] = l.array.strides(d);
  }
  return l;
}

/// Calls @p f(voxel, value) for every label of @p l as a T, voxels in C
/// order (x slowest), whatever the array's strides.
template <class T, class F>
void forEachLabel(const Labels& l, F&& f) {
  std::size_t v = 0;
  for (py::ssize_t i = 0; i < l.n[0]; ++i)
    for (py::ssize_t j = 0; j < l.n[1]; ++j) {
      const char* row = l.base + i * l.stride[0] + j * l.stride[1];
      for (py::ssize_t k = 0; k < l.n[2]; ++k, ++v) {
        T value;
        std::memcpy(&value, row + k * l.stride[2], sizeof(T));
        f(v, value);
      }
    }
}

/// Calls @p f(voxel, label as int64) for every label of @p l (any integer
/// dtype); an unsigned label above the int64 range is an error naming it.
template <class F>
void forEachLabel64(const Labels& l, F&& f) {
  auto call = [&](std::size_t v, auto value) { f(v, static_cast<std::int64_t>(value)); };
  auto call_u64 = [&](std::size_t v, std::uint64_t value) {
    if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      throw Error("label " + std::to_string(value) + " has no phase (phase ids are int64)",
                  {"", 0, "phases"});
    f(v, static_cast<std::int64_t>(value));
  };
  const bool s = l.kind == 'i';
  switch (l.itemsize) {
  case 1:
    return s ? forEachLabel<std::int8_t>(l, call) : forEachLabel<std::uint8_t>(l, call);
  case 2:
    return s ? forEachLabel<std::int16_t>(l, call) : forEachLabel<std::uint16_t>(l, call);
  case 4:
    return s ? forEachLabel<std::int32_t>(l, call) : forEachLabel<std::uint32_t>(l, call);
  case 8:
    return s ? forEachLabel<std::int64_t>(l, call) : forEachLabel<std::uint64_t>(l, call_u64);
  default:
    throwInput("labels: an integer dtype of " + std::to_string(l.itemsize) +
                   " bytes is not supported",
               "labels");
  }
}

/// Phase id -> its dict, sorted by id (phase 0, the matrix, is the smallest).
using PhaseDicts = std::vector<std::pair<std::int64_t, py::dict>>;

PhaseDicts phaseDicts(py::handle phases) {
  if (!py::hasattr(phases, "items") || py::isinstance<py::str>(phases))
    throwInput("phases must be a dict {id: {phase keys}}, got " + typeName(phases), "phases");
  PhaseDicts out;
  for (py::handle item : phases.attr("items")()) {
    const py::tuple kv = py::reinterpret_borrow<py::tuple>(item);
    const py::handle key = kv[0];
    int overflow = 1;
    long long id = 0;
    if (!py::isinstance<py::bool_>(key) && PyIndex_Check(key.ptr())) {
      const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(key.ptr()));
      id = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
    }
    if (overflow != 0)
      throwInput("phase ids (the keys of phases) must be integers, got " +
                     std::string(py::repr(key)),
                 "phases");
    const std::string where = "phases[" + std::to_string(id) + "]";
    if (!py::isinstance<py::dict>(kv[1]) && !py::hasattr(kv[1], "items"))
      throwInput("expected a dict of the keys of a cell file's [[phases]] table, got " +
                     typeName(kv[1]),
                 where);
    out.emplace_back(static_cast<std::int64_t>(id), py::dict(kv[1]));
  }
  if (out.empty())
    throwInput("phases is empty: give at least one phase (the smallest id is the matrix)",
               "phases");
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

/// Adds `size` (None: none; a number: a cube; 3 numbers) to @p cell.
void insertSize(toml::table& cell, py::handle size) {
  if (size.is_none())
    return;
  if (!py::isinstance<py::str>(size) && PySequence_Check(size.ptr())) {
    const py::sequence s = py::reinterpret_borrow<py::sequence>(size);
    if (s.size() != 3)
      throwInput("size must be one edge length (a cube) or 3, in metres; got " +
                     std::to_string(s.size()) + " values",
                 "size");
    toml::array edges;
    for (std::size_t d = 0; d < 3; ++d)
      edges.push_back(toDouble(s[d], "size"));
    cell.insert("size", std::move(edges));
    return;
  }
  cell.insert("size", toDouble(size, "size"));
}

/// The cell document of an array cell: [cell] resolution and size, one
/// [[phases]] table per dict (with id = its key), in id order.
std::string cellDocument(const Labels& l, const PhaseDicts& phases, py::handle size) {
  toml::table cell;
  cell.insert("resolution", toml::array{l.n[0], l.n[1], l.n[2]});
  insertSize(cell, size);
  toml::array tables;
  for (const auto& [id, dict] : phases) {
    const std::string where = "phases[" + std::to_string(id) + "]";
    toml::table t = toToml(dict, where);
    if (const auto given = t["id"].value<std::int64_t>(); t.contains("id") && given != id)
      throwInput("the id of a phase is its key in phases (" + std::to_string(id) +
                     "); leave id out",
                 where + ".id");
    t.insert_or_assign("id", id);
    tables.push_back(std::move(t));
  }
  toml::table doc;
  doc.insert("cell", std::move(cell));
  doc.insert("phases", std::move(tables));
  std::ostringstream os;
  os << doc;
  return os.str() + "\n";
}

/// Rewrites the key of an error of the reader about the generated document
/// into the from_array arguments: phases[i] (i-th in id order) -> phases[ID],
/// cell.size -> size.
[[noreturn]] void rethrowForArray(const Error& e, const PhaseDicts& phases) {
  ErrorContext c = e.context();
  if (c.file != kArraySource)
    throw e;
  c.line = 0; // lines of the generated document mean nothing to the caller
  std::string& k = c.key;
  if (k.rfind("cell.size", 0) == 0)
    k = k.substr(5);
  else if (k.rfind("cell.resolution", 0) == 0)
    k = "labels";
  else if (k.rfind("phases[", 0) == 0) {
    const std::size_t close = k.find(']');
    const std::size_t i = std::stoul(k.substr(7, close - 7));
    if (i < phases.size())
      k = "phases[" + std::to_string(phases[i].first) + "]" + k.substr(close + 1);
  }
  throw Error(e.message(), c);
}

/// Looks up the phase index of a label: a table over [min, max] when that
/// range is small, else a binary search of the sorted ids.
class PhaseLookup {
public:
  PhaseLookup(const PhaseDicts& phases, std::int64_t lo, std::int64_t hi) : lo_(lo) {
    for (const auto& p : phases)
      ids_.push_back(p.first);
    const double range = static_cast<double>(hi) - static_cast<double>(lo) + 1;
    if (range <= double(1 << 22)) {
      table_.assign(static_cast<std::size_t>(hi - lo + 1), -1);
      for (std::size_t p = 0; p < ids_.size(); ++p)
        if (ids_[p] >= lo && ids_[p] <= hi)
          table_[static_cast<std::size_t>(ids_[p] - lo)] = static_cast<std::int32_t>(p);
    }
  }
  /// @return the phase index of @p label, -1 if no phase has that id
  std::int32_t operator()(std::int64_t label) const {
    if (!table_.empty())
      return table_[static_cast<std::size_t>(label - lo_)];
    const auto it = std::lower_bound(ids_.begin(), ids_.end(), label);
    return it != ids_.end() && *it == label ? static_cast<std::int32_t>(it - ids_.begin()) : -1;
  }

private:
  std::int64_t lo_;
  std::vector<std::int64_t> ids_;
  std::vector<std::int32_t> table_;
};

[[noreturn]] void orphanError(const std::map<std::int64_t, std::size_t>& orphans,
                              const PhaseDicts& phases) {
  std::string list, ids;
  int shown = 0;
  for (const auto& [label, count] : orphans) {
    if (++shown > 10) {
      list += ", ...";
      break;
    }
    list += (list.empty() ? "" : ", ") + std::to_string(label) + " (" + std::to_string(count) +
            (count == 1 ? " voxel)" : " voxels)");
  }
  for (const auto& p : phases)
    ids += (ids.empty() ? "" : ", ") + std::to_string(p.first);
  throw Error("labels hold ids with no phase in phases: " + list + "; phases has ids " + ids,
              {"", 0, "phases"});
}

/// The phase map of @p l: a borrow of the array when it is int32, C order,
/// aligned and its ids are 0..P-1 (then @p copied is false), else one copy
/// with each label mapped to its phase index. An id with no phase is an
/// error naming it. The GIL is released while the labels are read.
micro::PhaseMap phaseMapOf(const Labels& l, const PhaseDicts& phases, bool& copied) {
  std::int64_t lo = std::numeric_limits<std::int64_t>::max(),
               hi = std::numeric_limits<std::int64_t>::min();
  {
    py::gil_scoped_release release;
    forEachLabel64(l, [&](std::size_t, std::int64_t v) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    });
  }
  const auto P = static_cast<std::int64_t>(phases.size());
  bool dense_ids = true; // the ids are 0..P-1: label = phase index
  for (std::size_t p = 0; p < phases.size(); ++p)
    dense_ids = dense_ids && phases[p].first == static_cast<std::int64_t>(p);
  const bool c_order = (l.array.flags() & py::array::c_style) != 0;
  const bool aligned = reinterpret_cast<std::uintptr_t>(l.base) % alignof(std::int32_t) == 0;
  if (l.kind == 'i' && l.itemsize == 4 && c_order && aligned && dense_ids && lo >= 0 && hi < P) {
    copied = l.converted;
    // the map keeps the array alive; the last reference is dropped with the GIL
    auto* holder = new py::object(l.array);
    std::shared_ptr<py::object> keeper(holder, [](py::object* o) {
      py::gil_scoped_acquire gil;
      delete o;
    });
    return micro::PhaseMap::borrow(reinterpret_cast<const std::int32_t*>(l.base), l.voxels(),
                                   std::move(keeper));
  }
  copied = true;
  std::vector<std::int32_t> map(l.voxels());
  std::map<std::int64_t, std::size_t> orphans;
  {
    py::gil_scoped_release release;
    const PhaseLookup lookup(phases, lo, hi);
    forEachLabel64(l, [&](std::size_t v, std::int64_t label) {
      const std::int32_t p = lookup(label);
      if (p < 0)
        ++orphans[label];
      map[v] = p;
    });
  }
  if (!orphans.empty())
    orphanError(orphans, phases);
  return micro::PhaseMap(std::move(map));
}

/// The provenance text of an array cell: what it is, then its document.
std::string arrayDescription(const CellData& d, const Labels& l, const std::string& document) {
  std::ostringstream os;
  os << "# lamina.Cell.from_array: " << d.cell.n[0] << " x " << d.cell.n[1] << " x " << d.cell.n[2]
     << " voxels (axis 0 = x), " << d.spec.phases.size() << " phases, labels "
     << std::string(py::str(l.array.dtype())) << ", "
     << ((l.array.flags() & py::array::c_style) ? "C order" : "not C order")
     << (d.copied ? ", copied" : ", used in place") << "\n# phase map (int32 phase indices, C "
     << "order, x slowest) checksum " << phaseMapChecksum(d.cell) << "\n";
  return os.str() + document;
}

std::shared_ptr<CellData> fromArray(hint::Labels labels, hint::Phases phases, hint::Size size,
                                    hint::OptionalPath catalog) {
  auto data = std::make_shared<CellData>();
  data->source = kArraySource;
  const PhaseDicts dicts = phaseDicts(phases);
  const Labels l = labelsOf(labels);
  const std::string document = cellDocument(l, dicts, size);
  try {
    data->spec = micro::readCellString(document, kArraySource, catalogOf(catalog));
  } catch (const Error& e) {
    rethrowForArray(e, dicts);
  }
  micro::UnitCell& cell = data->cell;
  cell.n = {static_cast<int>(l.n[0]), static_cast<int>(l.n[1]), static_cast<int>(l.n[2])};
  cell.size = data->spec.size;
  cell.phase_count = static_cast<int>(data->spec.phases.size());
  cell.phase = phaseMapOf(l, dicts, data->copied);
  cell.countFractions();
  data->spec.text = arrayDescription(*data, l, document);
  if (cell.phase.borrowed())
    data->labels_checksum = phaseMapChecksum(cell);
  return data;
}

// ---------------------------------------------------------------- the class

py::array phaseMapView(const std::shared_ptr<CellData>& d, py::handle self) {
  const auto& n = d->cell.n;
  const auto s = static_cast<py::ssize_t>(sizeof(std::int32_t));
  py::array_t<std::int32_t> view({static_cast<py::ssize_t>(n[0]), static_cast<py::ssize_t>(n[1]),
                                  static_cast<py::ssize_t>(n[2])},
                                 {s * n[1] * n[2], s * n[2], s}, d->cell.phase.data(), self);
  view.attr("setflags")(py::arg("write") = false);
  return std::move(view);
}

py::dict phaseFractions(const CellData& d) {
  py::dict out;
  for (std::size_t p = 0; p < d.spec.phases.size(); ++p)
    out[py::str(d.spec.phases[p].name)] = d.cell.voxel_fraction.at(p);
  return out;
}

std::string reprOf(const CellData& d) {
  const auto& n = d.cell.n;
  return "<lamina.Cell " + std::string(py::repr(py::str(d.source))) + ": " + std::to_string(n[0]) +
         " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) + " voxels, " +
         std::to_string(d.spec.phases.size()) + " phases>";
}

} // namespace

std::string phaseMapChecksum(const micro::UnitCell& cell) {
  core::Fnv1a h;
  h.add(cell.phase.data(), cell.phase.size() * sizeof(std::int32_t));
  return "fnv1a64:" + h.hex();
}

std::shared_ptr<const CellData> cellData(py::handle cell, const std::string& key) {
  if (!py::isinstance<CellData>(cell))
    throwInput("expected a lamina.Cell (Cell.from_file or Cell.from_array), got " + typeName(cell),
               key);
  return cell.cast<std::shared_ptr<CellData>>();
}

void checkUnchanged(const CellData& cell) {
  if (!cell.labels_checksum.empty() && phaseMapChecksum(cell.cell) != cell.labels_checksum)
    throwInput("the label array of this cell changed after Cell.from_array (the cell reads it "
               "in place; its voxel fractions and provenance are those of the old labels): "
               "make the cell again",
               "labels");
}

void bindCell(py::module_& m) {
  py::class_<CellData, std::shared_ptr<CellData>> c(
      m, "Cell", "A periodic voxel unit cell with its phases' laws.");
  c.def_static("from_file", &fromFile, py::arg("path"), py::arg("set") = py::none(),
               py::arg("catalog") = py::none(),
               "Reads any cell file (generated inclusions, image cells) and builds\n"
               "its voxels, as `micro` and `homogenize` do. `set` holds\n"
               "{\"cell.resolution\": 16, ...}: the programs' --set KEY=VALUE.");
  c.def_static("from_array", &fromArray, py::arg("labels"), py::arg("phases"),
               py::arg("size") = py::none(), py::arg("catalog") = py::none(),
               "A cell from a 3D integer array of phase ids, axis 0 = x, axis 1 =\n"
               "y, axis 2 = z (any integer dtype, C or Fortran order), and a dict\n"
               "phase id -> the keys of a cell file's [[phases]] table (name, law or\n"
               "catalog, E, nu, density...). `size`: edge lengths in metres (None:\n"
               "a scale-free cell of edge 1, no dispersion). The array is used\n"
               "without a copy when it is int32, C-contiguous and its ids are\n"
               "0..P-1 in the dict; otherwise it is copied (Cell.copied says which).\n"
               "A cell using the array in place reads it: homogenize refuses a cell\n"
               "whose array changed since.");
  c.def(
      "phase_map",
      [](py::object self) { return phaseMapView(self.cast<std::shared_ptr<CellData>>(), self); },
      "The phase index per voxel, shape resolution, axis 0 = x; a\n"
      "read-only view of the cell's own array (no copy).");
  c.def_property_readonly("resolution", [](const CellData& d) {
    return py::make_tuple(d.cell.n[0], d.cell.n[1], d.cell.n[2]);
  });
  c.def_property_readonly("size", [](const CellData& d) {
    return py::make_tuple(d.cell.size[0], d.cell.size[1], d.cell.size[2]);
  });
  c.def_property_readonly("phase_names", [](const CellData& d) {
    py::list names;
    for (const auto& p : d.spec.phases)
      names.append(p.name);
    return names;
  });
  c.def_property_readonly("phase_fractions", &phaseFractions,
                          "Voxel fraction of each phase (cut voxels split by their fractions).");
  c.def_property_readonly(
      "copied", [](const CellData& d) { return d.copied; },
      "from_array: whether the label array was copied.");
  c.def_property_readonly(
      "source", [](const CellData& d) { return d.source; },
      "The cell file's path, or \"<array>\".");
  c.def("__repr__", &reprOf);
}

} // namespace lamina::python
