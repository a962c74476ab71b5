/// @file laws.cpp
/// @brief Python bindings: see common.hpp (bindLaws) and python/lamina/__init__.pyi.
///
/// lamina.drive is `materials drive` without its files: the same checks of
/// the path, rate and final strain, the same law lookup (library, then
/// catalog, reduced-order entries included: MaterialSource::law) or a dict
/// read by the law reader of cell phases and case sections (readLawSpec),
/// the same materials::drive, and its rows as the columns of the CSV.
#include "python/src/convert.hpp"

#include "core/interrupt.hpp"
#include "core/progress.hpp"
#include "core/toml_reader.hpp"
#include "materials/law_spec.hpp"
#include "materials/material_source.hpp"
#include "materials/point_driver.hpp"

#include <pybind11/numpy.h>

#include <sstream>
#include <string>
#include <vector>

namespace lamina::python {

namespace {

namespace mat = lamina::materials;

/// Where the dict of a law is in messages ("material.E").
constexpr const char* kMaterialKey = "material";

/// What drive() is to do: the options and where its law comes from.
struct DriveRequest {
  mat::DriveOptions options;
  std::string name;    ///< a library or catalog name, or "" for a dict law
  toml::table law;     ///< the dict law as TOML (name empty)
  std::string library; ///< library file ("": the default)
  std::string catalog; ///< catalog file ("": the default)
};

/// @return @p steps as the CLI's --steps takes it: an int in [1, 1e8]
int stepsArgument(py::handle steps) {
  const long long value = toInt(steps, "steps");
  if (value < 1 || value > 100000000)
    throwInput("steps per leg must be in [1, 100000000], got " + std::to_string(value), "steps");
  return static_cast<int>(value);
}

/// The law of a dict: readLawSpec over its TOML form; a key no law reads is
/// an error naming it and the law.
mat::LawPtr dictLaw(const toml::table& table) {
  const core::TableReader reader(table, "", kMaterialKey);
  const mat::LawSpec spec = mat::readLawSpec(reader);
  try {
    reader.finish();
  } catch (const Error& e) {
    throwInput(std::string("not a key of law \"") + mat::toString(spec.kind) +
                   "\" (a law dict holds `law` and that law's keys)",
               e.context().key);
  }
  try { // the law's own checks of its parameters (GvboLaw: Et < E0, ...)
    return spec.make();
  } catch (const Error& e) {
    if (!e.context().key.empty())
      throw;
    throwInput(e.message(),
               std::string(kMaterialKey) + (spec.kind == mat::LawKind::Gvbo ? ".gvbo" : ".law"));
  }
}

/// Reads the arguments of lamina.drive, checked as `materials drive` checks
/// its options (the names of Python's arguments in the messages).
DriveRequest driveRequest(py::handle material, py::handle path, py::handle rate, py::handle to,
                          py::handle steps, bool unload, py::handle kinematics, py::handle library,
                          py::handle catalog) {
  DriveRequest r;
  mat::DriveOptions& o = r.options;
  o.path =
      mat::kDrivePathNames.parseOrThrow(strArgument(path, "path"), "strain path", {"", 0, "path"});
  o.kinematics = mat::kKinematicsNames.parseOrThrow(strArgument(kinematics, "kinematics"),
                                                    "kinematics", {"", 0, "kinematics"});
  o.rate = toDouble(rate, "rate", false);
  mat::checkRate(o.rate, "rate");
  o.to = toDouble(to, "to", false);
  mat::checkFinalStrain(o.path, o.to, "to");
  o.steps = stepsArgument(steps);
  o.unload = unload;
  r.library = pathArgument(library, "library");
  r.catalog = pathArgument(catalog, "catalog");
  if (py::isinstance<py::str>(material)) {
    r.name = material.cast<std::string>();
  } else if (py::isinstance(material, py::module_::import("collections.abc").attr("Mapping"))) {
    r.law = toToml(py::dict(py::reinterpret_borrow<py::object>(material)), kMaterialKey);
  } else {
    throwInput("expected a material name (str) or a dict of law keys (law = \"gvbo\", E, nu, "
               "...), got " +
                   typeName(material),
               kMaterialKey);
  }
  return r;
}

/// Thrown by the step observer to leave materials::drive (not a
/// lamina::Error, which drive() would wrap as a failed step).
struct Stopped {
  int signal; ///< the signal that asked to stop
  int step;   ///< the step it was seen after
};

/// Runs @p r (GIL released: no Python here): the law found, the point
/// driven with a progress line (quiet: only LongCall's callback sees it)
/// and a stop at the step after an interrupt.
std::vector<mat::DriveRow> runDrive(const DriveRequest& r) {
  mat::LawPtr law;
  if (r.name.empty()) {
    law = dictLaw(r.law);
  } else {
    mat::MaterialSource source(r.library, r.catalog);
    law = source.law(r.name);
  }
  const mat::DriveOptions& o = r.options;
  const int total = o.unload ? 2 * o.steps : o.steps;
  core::ProgressLine line("drive steps", total, true);
  const auto observer = [&](const mat::DriveStep& s) {
    line.update(s.n);
    if (const int signal = core::interruptSignal())
      throw Stopped{signal, s.n};
  };
  try {
    std::vector<mat::DriveRow> rows = mat::drive(*law, o, observer);
    line.finish();
    return rows;
  } catch (const Stopped& s) {
    std::ostringstream os;
    os << "drive stopped by " << core::signalName(s.signal) << " at step " << s.step << " of "
       << total << " (nothing returned)";
    throw Interrupted(s.signal, os.str());
  }
}

/// @return @p rows as the columns of `materials drive`'s CSV (kDriveHeader), in its order
py::dict driveColumns(const std::vector<mat::DriveRow>& rows) {
  std::vector<std::string> names;
  std::istringstream header(mat::kDriveHeader);
  for (std::string name; std::getline(header, name, ',');)
    names.push_back(name);
  const auto n = static_cast<py::ssize_t>(rows.size());
  py::dict out;
  for (std::size_t c = 0; c < names.size(); ++c) {
    py::array_t<double> column(n);
    auto v = column.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const mat::DriveRow& row = rows[static_cast<std::size_t>(i)];
      v(i) = c == 0   ? row.t
             : c <= 6 ? row.eps[static_cast<int>(c - 1)]
                      : row.sigma[static_cast<int>(c - 7)];
    }
    out[py::str(names[c])] = column;
  }
  return out;
}

py::dict drivePy(hint::Material material, hint::Str path, hint::Float rate, hint::Float to,
                 hint::Int steps, bool unload, hint::Str kinematics, hint::OptionalPath library,
                 hint::OptionalPath catalog, hint::Progress progress) {
  const DriveRequest request =
      driveRequest(material, path, rate, to, steps, unload, kinematics, library, catalog);
  LongCall call(std::move(progress));
  std::vector<mat::DriveRow> rows;
  call.run([&] { rows = runDrive(request); });
  return driveColumns(rows);
}

} // namespace

void bindLaws(py::module_& m) {
  m.def("drive", &drivePy, py::arg("material"), py::arg("path") = "uniaxial-strain",
        py::arg("rate") = 1.0, py::arg("to") = 0.1, py::arg("steps") = 200,
        py::arg("unload") = false, py::arg("kinematics") = "finite",
        py::arg("library") = py::none(), py::arg("catalog") = py::none(),
        py::arg("progress") = py::none(),
        "A material law driven point by point (`materials drive`): column ->\n"
        "array, the columns of its CSV. `material`: a library or catalog name,\n"
        "or a dict with the keys of a law (law = \"gvbo\", ...).");
}

} // namespace lamina::python
