/// @file library.cpp
/// @brief Python bindings: see common.hpp (bindLibrary) and python/lamina/__init__.pyi.
///
/// lamina.Library holds the library's path (and the catalog's), never its
/// entries: every call reads the file again, as a program started then
/// would, so a Library sees what the programs (or another Library) wrote
/// after it was made. Reads are those of `materials show --json`
/// (materials::showJson); writes are the programs' transactions
/// (materials::Library::add and remove: locked, atomic, checked).

#include "python/src/convert.hpp"
#include "python/src/homogenize.hpp"

#include "materials/entries.hpp"
#include "materials/export.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <utility>
#include <vector>

namespace lamina::python {

namespace {

namespace mat = lamina::materials;

/// The provenance `program` of the entries written from Python.
constexpr const char* kAddFromCatalogProgram = "lamina.Library.add_from_catalog";
constexpr const char* kLayupProgram = "lamina.Library.layup";

/// lamina.Library: where the library and the catalog are; nothing else.
class PyLibrary {
public:
  /// @param path library file ("": --library's default, Library::resolvePath)
  /// @param catalog catalog file ("": Catalog::defaultPath())
  PyLibrary(const std::string& path, std::string catalog)
      : path_(std::filesystem::absolute(mat::Library::resolvePath(path))),
        catalog_(catalog.empty() ? std::string() : std::filesystem::absolute(catalog).string()) {
    load(); // a malformed file is an error now, not at the first access
  }

  /// @return the library as it is on disk now
  mat::Library load() const { return mat::Library(path_); }
  /// @return the library file
  const std::filesystem::path& path() const { return path_; }
  /// @return the catalog file (given or default)
  std::filesystem::path catalogFile() const {
    return catalog_.empty() ? mat::Catalog::defaultPath() : std::filesystem::path(catalog_);
  }
  /// @return the catalog argument of MaterialSource ("" for the default)
  const std::string& catalog() const { return catalog_; }

private:
  std::filesystem::path path_;
  std::string catalog_;
};

/// @return the 6x6 JSON rows @p rows (matrixToJson) as a (6, 6) float64 array
py::array_t<double> matrixArray(const nlohmann::json& rows) {
  py::array_t<double> a({6, 6});
  auto view = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < 6; ++i)
    for (py::ssize_t k = 0; k < 6; ++k)
      view(i, k) = rows.at(static_cast<std::size_t>(i)).at(static_cast<std::size_t>(k));
  return a;
}

/// @return `materials show NAME --json` of @p m as a dict, its 6x6
/// matrices (C, dispersion, each phase's C) as numpy arrays
py::dict entryDict(const mat::Library& library, const mat::Material& m) {
  const nlohmann::json j = mat::showJson(library, m);
  py::dict d = toPython(j);
  for (const char* key : {"C", "dispersion"})
    if (j.contains(key))
      d[key] = matrixArray(j.at(key));
  if (j.contains("phases")) {
    py::list phases = d["phases"];
    for (std::size_t p = 0; p < j.at("phases").size(); ++p)
      phases[p]["C"] = matrixArray(j.at("phases").at(p).at("C"));
  }
  return d;
}

/// lib[name]: the entry, or KeyError naming it and the library file.
py::dict getItem(const PyLibrary& self, hint::Str name) {
  if (!py::isinstance<py::str>(name))
    throw py::key_error(py::repr(name).cast<std::string>());
  const mat::Library library = self.load();
  const mat::Material* entry = nullptr;
  try {
    entry = &library.get(name.cast<std::string>());
  } catch (const Error& e) { // its message: the name, the file and what it holds
    throw py::key_error(e.message());
  }
  return entryDict(library, *entry);
}

/// The plies of Library.layup: a sequence of (material, angle in degrees,
/// thickness in m).
std::vector<mat::Ply> pliesArgument(py::handle plies) {
  const auto sequence = [](py::handle o) {
    return PySequence_Check(o.ptr()) && !py::isinstance<py::str>(o) &&
           !py::isinstance<py::bytes>(o);
  };
  if (!sequence(plies))
    throwInput("plies must be a sequence of (material, angle_deg, thickness_m) tuples, got " +
                   typeName(plies),
               "plies");
  std::vector<mat::Ply> out;
  std::size_t i = 0;
  for (py::handle item : py::reinterpret_borrow<py::sequence>(plies)) {
    const std::string key = "plies[" + std::to_string(i++) + "]";
    if (!sequence(item) || py::len(item) != 3)
      throwInput("a ply is a (material, angle_deg, thickness_m) tuple, got " +
                     std::string(py::repr(item)),
                 key);
    const py::sequence ply = py::reinterpret_borrow<py::sequence>(item);
    mat::Ply p;
    p.material = strArgument(ply[0], key + ".material");
    p.angle_deg = toDouble(ply[1], key + ".angle_deg");
    p.thickness = toDouble(ply[2], key + ".thickness");
    out.push_back(std::move(p));
  }
  return out;
}

/// Library.add_from_catalog: `materials add NAME --from-catalog KEY`.
void addFromCatalog(const PyLibrary& self, hint::Str name, hint::Str catalog_name, bool overwrite) {
  const std::string n = strArgument(name, "name");
  const std::string key = strArgument(catalog_name, "catalog_name");
  py::gil_scoped_release unlocked; // the library's lock may wait on another process
  const mat::Catalog catalog(self.catalogFile());
  self.load().add(mat::catalogEntry(catalog, key, n, kAddFromCatalogProgram), overwrite);
}

/// Library.layup: `materials layup NAME --ply M:A:T ...`.
void addLayup(const PyLibrary& self, hint::Str name, hint::Plies plies, bool overwrite) {
  const std::string n = strArgument(name, "name");
  const std::vector<mat::Ply> stack = pliesArgument(plies);
  py::gil_scoped_release unlocked; // the library's lock may wait on another process
  mat::MaterialSource source(self.path().string(), self.catalog());
  const mat::Material m = mat::layupEntry(n, stack, source, kLayupProgram);
  self.load().add(m, overwrite);
}

/// Library.export: `materials export NAME --format FORMAT`.
std::string exportEntry(const PyLibrary& self, hint::Str name, hint::Str format) {
  const std::string n = strArgument(name, "name");
  const mat::ExportFormat f = mat::kExportFormatNames.parseOrThrow(
      strArgument(format, "format"), "export format", {"", 0, "format"});
  const mat::Library library = self.load();
  return mat::exportCard(library.get(n), f);
}

/// The Mapping methods (lib[name], in, iteration, len, keys, items, values, get).
void bindMapping(py::class_<PyLibrary>& cls) {
  cls.def("__getitem__", &getItem, py::arg("name"))
      .def(
          "__contains__",
          [](const PyLibrary& self, py::object name) {
            return py::isinstance<py::str>(name) && self.load().contains(name.cast<std::string>());
          },
          py::arg("name"))
      .def("__iter__",
           [](const PyLibrary& self) { return py::iter(py::cast(self.load().names())); })
      .def("__len__", [](const PyLibrary& self) { return self.load().names().size(); })
      .def(
          "get",
          [](const PyLibrary& self, py::object name, py::object fallback) -> py::object {
            if (!py::isinstance<py::str>(name))
              return fallback;
            const mat::Library library = self.load();
            const std::string key = name.cast<std::string>();
            return library.contains(key) ? py::object(entryDict(library, library.get(key)))
                                         : fallback;
          },
          py::arg("name"), py::arg("default") = py::none(),
          "The entry `name`, or `default` when the library has none of that name.")
      .def("__repr__", [](const PyLibrary& self) {
        return "lamina.Library(" + py::repr(py::str(self.path().string())).cast<std::string>() +
               ")";
      });
  const py::module_ abc = py::module_::import("collections.abc");
  const std::pair<const char*, const char*> views[] = {
      {"keys", "KeysView"}, {"items", "ItemsView"}, {"values", "ValuesView"}};
  for (const auto& [method, view] : views) {
    const py::object type = abc.attr(view);
    cls.def(
        method, [type](py::object self) { return type(self); },
        "A view of the library, read from the file on each use (collections.abc).");
  }
  abc.attr("Mapping").attr("register")(cls);
}

} // namespace

void bindLibrary(py::module_& m) {
  py::class_<PyLibrary> cls(m, "Library",
                            "The materials library file: a mapping name -> entry (the fields of\n"
                            "`materials show --json`, C as a 6x6 array). Writes are atomic and\n"
                            "locked, as the programs'. Nothing is cached: every access reads the\n"
                            "file again, so a Library sees what the programs wrote after it was\n"
                            "made; a name it lacks raises KeyError naming the file.");
  cls.def(py::init([](hint::OptionalPath path, hint::OptionalPath catalog) {
            return PyLibrary(pathArgument(path, "path"), pathArgument(catalog, "catalog"));
          }),
          py::arg("path") = py::none(), py::arg("catalog") = py::none(),
          "path None: --library's default ($LAMINA_LIBRARY, then the XDG path).")
      .def_property_readonly("path", [](const PyLibrary& self) { return self.path().string(); });
  bindMapping(cls);
  cls.def(
         "add",
         [](const PyLibrary& self, hint::Str name, hint::ResultArg result, bool overwrite) {
           mat::Library library = self.load();
           addHomogenized(result, library, strArgument(name, "name"), overwrite);
         },
         py::arg("name"), py::arg("result"), py::arg("overwrite") = false,
         "Adds a homogenized entry with its provenance (as `homogenize --name`).")
      .def("add_from_catalog", &addFromCatalog, py::arg("name"), py::arg("catalog_name"),
           py::arg("overwrite") = false,
           "Adds the catalog material `catalog_name` as entry `name` (as\n"
           "`materials add NAME --from-catalog KEY`).")
      .def("layup", &addLayup, py::arg("name"), py::arg("plies"), py::arg("overwrite") = false,
           "plies: (material, angle in degrees, thickness in m), bottom first.")
      .def("export", &exportEntry, py::arg("name"), py::arg("format") = "json",
           "The text `materials export NAME --format FORMAT` prints.")
      .def(
          "remove",
          [](const PyLibrary& self, hint::Str name) {
            const std::string n = strArgument(name, "name");
            py::gil_scoped_release unlocked; // the lock may wait on another process
            self.load().remove(n);
          },
          py::arg("name"), "Removes entry `name` (as `materials remove NAME`).");
}

} // namespace lamina::python
