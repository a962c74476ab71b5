/// @file homogenize.cpp
/// @brief Python bindings: lamina.homogenize, lamina.HomogenizeResult and
/// lamina.homogenize_path (python/lamina/__init__.pyi), and
/// addHomogenized (homogenize.hpp). The computations are those of the
/// `homogenize` program with its defaults: homogenize::homogenizeCell and
/// makeEntry for `homogenize CELL --name N`, homogenize::runPath (no output
/// files) for `homogenize CELL --path P --out F.csv`.
#include "python/src/homogenize.hpp"

#include "core/names.hpp"
#include "core/resources.hpp"
#include "homogenize/library_entry.hpp"
#include "homogenize/memory_estimate.hpp"
#include "homogenize/nonlinear_run.hpp"
#include "materials/point_driver.hpp"
#include "micro/phase_map_io.hpp"
#include "python/src/cell.hpp"

#include <pybind11/numpy.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace lamina::python {

/// A lamina.HomogenizeResult: the solve's result and what Library.add
/// writes (the entry without its name, and the cell for its side file).
struct HomogenizeData {
  std::shared_ptr<const CellData> cell; ///< the cell homogenized (its phase map: the side file)
  homogenize::EntryResult entry;        ///< C, density, diagnostics, dispersion
  materials::Material material;         ///< the library entry with its provenance, unnamed
};

namespace {

/// The `program` a library entry of the module records in its provenance.
constexpr const char* kProgram = "homogenize (lamina Python module: lamina.homogenize)";

/// @return the solver threads of @p threads (None: the programs' default, 0 = auto)
int threadsOf(py::handle threads) {
  if (threads.is_none())
    return 0;
  const long long n = toInt(threads, "threads");
  if (n < 0 || n > 1 << 20)
    throwInput("must be in [0, hardware threads], got " + std::to_string(n), "threads");
  core::checkThreads(static_cast<int>(n), "threads");
  return static_cast<int>(n);
}

/// @return @p tol (None: the program's default), checked as --tol is (positive)
double tolOf(py::handle tol, double fallback) {
  if (tol.is_none())
    return fallback;
  const double t = toDouble(tol, "tol");
  if (!(t > 0))
    throwInput("tol must be positive, got " + std::string(py::str(tol)), "tol");
  return t;
}

py::array_t<double> matrixArray(const materials::Matrix6& c) {
  py::array_t<double> a({6, 6});
  auto m = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < 6; ++i)
    for (py::ssize_t j = 0; j < 6; ++j)
      m(i, j) = c(i, j);
  return a;
}

/// @return @p n (a TOML value, array or table) as Python objects
py::object tomlToPython(const toml::node& n) {
  if (const toml::table* t = n.as_table()) {
    py::dict d;
    for (const auto& [k, v] : *t)
      d[py::str(std::string(k.str()))] = tomlToPython(v);
    return std::move(d);
  }
  if (const toml::array* a = n.as_array()) {
    py::list l;
    for (const toml::node& v : *a)
      l.append(tomlToPython(v));
    return std::move(l);
  }
  if (const auto* s = n.as_string())
    return py::str(s->get());
  if (const auto* i = n.as_integer())
    return py::int_(i->get());
  if (const auto* f = n.as_floating_point())
    return py::float_(f->get());
  if (const auto* b = n.as_boolean())
    return py::bool_(b->get());
  std::ostringstream os; // dates and times: their TOML text
  n.visit([&](const auto& v) { os << v; });
  return py::str(os.str());
}

/// Refuses, as the program does before it allocates, a cell whose solve
/// with @p opt does not fit in memory (lamina.InputError with the amount).
void requireSolveMemory(const CellData& c, const homogenize::Options& opt) {
  const std::array<int, 3>& n = c.cell.n;
  core::requireMemory(
      homogenize::linearSolveBytes(std::uint64_t(n[0]) * std::uint64_t(n[1]) * std::uint64_t(n[2]),
                                   opt, c.spec.physical_size),
      "homogenizing " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
          std::to_string(n[2]) + " voxels",
      {c.source, 0, ""},
      "a coarser cell, or tol >= 1e-4 (single precision), or the program under mpirun "
      "(each rank holds 1/N of the fields)");
}

std::shared_ptr<HomogenizeData> homogenizeCell(hint::CellArg cell, hint::OptionalFloat tol,
                                               hint::OptionalInt threads, hint::Float J,
                                               hint::Progress progress) {
  const std::shared_ptr<const CellData> c = cellData(cell);
  checkUnchanged(*c);
  homogenize::Options opt; // the program's defaults (--fftw-plan auto, --estimate energy...)
  opt.tol = tolOf(tol, opt.tol);
  opt.threads = threadsOf(threads);
  opt.measure = -1;
  opt.quiet = true; // progress goes to the callback only
  const double j = toDouble(J, "J");
  if (!(j > 0))
    throwInput("volume ratio J must be positive, got " + std::string(py::str(J)), "J");
  requireSolveMemory(*c, opt);
  auto data = std::make_shared<HomogenizeData>();
  data->cell = c;
  LongCall(py::reinterpret_borrow<py::object>(progress)).run([&] {
    homogenize::EntryResult& e = data->entry;
    e = homogenize::homogenizeCell(c->spec, c->cell, "", j, opt);
    data->material = homogenize::makeEntry("", c->spec, c->cell, e.result, opt, j,
                                           e.dispersion ? &*e.dispersion : nullptr);
    data->material.provenance.insert_or_assign("program", kProgram);
  });
  return data;
}

/// The strain path of homogenize_path, checked as the program checks
/// --path, --rate, --to, --steps and --unload.
homogenize::PathSpec pathSpecOf(py::handle path, py::handle rate, py::handle to, py::handle steps,
                                py::handle unload) {
  homogenize::PathSpec p;
  if (!py::isinstance<py::str>(path))
    throwInput("path must be a str (" + materials::kDrivePathNames.list('"') + "), got " +
                   typeName(path),
               "path");
  const std::string name = path.cast<std::string>();
  const auto parsed = materials::kDrivePathNames.parse(name);
  if (!parsed)
    throwInput("unknown path \"" + name + "\" (expected " + materials::kDrivePathNames.list('"') +
                   ")",
               "path");
  p.path = *parsed;
  p.rate = toDouble(rate, "rate");
  materials::checkRate(p.rate, "rate");
  p.to = toDouble(to, "to");
  materials::checkFinalStrain(p.path, p.to, "to");
  const long long n = toInt(steps, "steps");
  if (n < 1 || n > 10000000)
    throwInput("steps must be in [1, 10000000], got " + std::to_string(n), "steps");
  p.steps = static_cast<int>(n);
  if (!py::isinstance<py::bool_>(unload))
    throwInput("unload must be True or False, got " + typeName(unload), "unload");
  p.unload = unload.cast<bool>();
  return p;
}

/// @return the columns of the CSV `homogenize --path --out` writes, in its
/// order: the header of `materials drive` and newton, krylov, residual,
/// wall_s; a row at t = 0 first, then one per step
py::dict pathColumns(const std::vector<homogenize::StepResult>& steps) {
  std::vector<std::string> names;
  std::stringstream header(std::string(materials::kDriveHeader) + ",newton,krylov,residual,wall_s");
  for (std::string name; std::getline(header, name, ',');)
    names.push_back(name);
  const auto rows = static_cast<py::ssize_t>(steps.size() + 1);
  std::vector<py::array_t<double>> columns;
  for (std::size_t c = 0; c < names.size(); ++c) {
    columns.emplace_back(rows);
    std::fill_n(columns.back().mutable_data(), rows, 0.0); // the row at t = 0
  }
  for (std::size_t r = 0; r < steps.size(); ++r) {
    const homogenize::StepResult& s = steps[r];
    std::vector<double> row{s.t};
    for (int a = 0; a < 6; ++a)
      row.push_back(s.E[a]);
    for (int a = 0; a < 6; ++a)
      row.push_back(s.Sigma[a]);
    row.insert(row.end(), {double(s.newton), double(s.krylov), s.residual, s.wall_s});
    for (std::size_t c = 0; c < names.size(); ++c)
      columns[c].mutable_data()[r + 1] = row[c];
  }
  py::dict out;
  for (std::size_t c = 0; c < names.size(); ++c)
    out[py::str(names[c])] = columns[c];
  return out;
}

py::dict homogenizePath(hint::CellArg cell, hint::Str path, hint::Float rate, hint::Float to,
                        hint::Int steps, hint::Bool unload, hint::OptionalInt threads,
                        hint::Progress progress) {
  const std::shared_ptr<const CellData> c = cellData(cell);
  checkUnchanged(*c);
  const homogenize::PathSpec spec = pathSpecOf(path, rate, to, steps, unload);
  homogenize::NonlinearOptions nl; // the program's defaults: --tol 1e-5, --eta 0.1
  nl.tol = 1e-5;
  nl.eta = 0.1;
  nl.threads = threadsOf(threads);
  nl.measure = -1;
  std::vector<homogenize::StepResult> results;
  LongCall(py::reinterpret_borrow<py::object>(progress)).run([&] {
    results = homogenize::runPath(c->spec, c->cell, spec, nl, {}, {});
  });
  return pathColumns(results);
}

void bindResult(py::module_& m) {
  using R = HomogenizeData;
  py::class_<R, std::shared_ptr<R>> r(m, "HomogenizeResult",
                                      "What lamina.homogenize returns (the `homogenize --json` "
                                      "fields).");
  r.def_property_readonly(
      "C", [](const R& d) { return matrixArray(d.entry.result.C.matrix()); },
      "6x6 effective stiffness, Pa, lamina order");
  r.def_property_readonly(
      "density", [](const R& d) { return d.entry.result.density; }, "kg/m^3");
  r.def_property_readonly(
      "dispersion",
      [](const R& d) -> py::object {
        if (!d.entry.dispersion)
          return py::none();
        return matrixArray(d.entry.dispersion->D);
      },
      "6x6 micro-inertia tensor zeta^2 D_lin, kg/m; None for a cell without size");
  r.def_property_readonly(
      "iterations",
      [](const R& d) {
        py::list l;
        for (int it : d.entry.result.iterations())
          l.append(it);
        return l;
      },
      "CG iterations of each of the six load cases");
  r.def_property_readonly(
      "residual", [](const R& d) { return d.entry.result.maxResidual(); },
      "largest final relative residual of the six load cases");
  r.def_property_readonly(
      "symmetry", [](const R& d) { return materials::toString(d.entry.result.symmetry.cls); },
      "symmetry class of C");
  r.def_property_readonly(
      "phase_fractions",
      [](const R& d) {
        py::dict f;
        const auto& phases = d.cell->spec.phases;
        for (std::size_t p = 0; p < phases.size(); ++p)
          f[py::str(phases[p].name)] = d.entry.result.voxel_fraction.at(p);
        return f;
      },
      "voxel fraction of each phase (cut voxels split by their fractions)");
  r.def_property_readonly(
      "provenance", [](const R& d) { return tomlToPython(d.material.provenance); },
      "what a library entry records (Library.add)");
  r.def_property_readonly(
      "wall_s", [](const R& d) { return d.entry.result.wall_s; }, "wall time of the solve, s");
  r.def("__repr__", [](const R& d) {
    return "<lamina.HomogenizeResult of " + std::string(py::repr(py::str(d.cell->source))) +
           ": density " + std::to_string(d.entry.result.density) + " kg/m^3, symmetry " +
           materials::toString(d.entry.result.symmetry.cls) + ">";
  });
}

} // namespace

void bindHomogenize(py::module_& m) {
  bindResult(m);
  m.def("homogenize", &homogenizeCell, py::arg("cell"), py::arg("tol") = py::none(),
        py::arg("threads") = py::none(), py::arg("J") = 1.0, py::arg("progress") = py::none(),
        "Effective stiffness, density and (cells with a size) dispersion\n"
        "tensor; the same solve as `homogenize CELL` (its defaults). J: the\n"
        "state of a gvbo phase (a cell file's list of J states is the program's\n"
        "sweep, one entry per J; here one J per call).");
  m.def("homogenize_path", &homogenizePath, py::arg("cell"), py::arg("path") = "uniaxial-strain",
        py::arg("rate") = 1e4, py::arg("to") = 0.1, py::arg("steps") = 100,
        py::arg("unload") = false, py::arg("threads") = py::none(),
        py::arg("progress") = py::none(),
        "The nonlinear cell along a strain path (`homogenize CELL --path`):\n"
        "column -> array, the columns of its CSV (t, eps_xx..eps_xz,\n"
        "sig_xx..sig_xz, newton, krylov, residual, wall_s).");
}

void addHomogenized(py::handle result, materials::Library& library, const std::string& name,
                    bool overwrite) {
  if (!py::isinstance<HomogenizeData>(result))
    throwInput("expected a lamina.HomogenizeResult (what lamina.homogenize returns), got " +
                   typeName(result),
               "result");
  const auto data = result.cast<std::shared_ptr<HomogenizeData>>();
  core::checkName(name, "entry name", {"", 0, "name"});
  homogenize::checkPercolates(data->cell->spec, data->entry.result.C);
  materials::Material m = data->material;
  m.name = name;
  std::vector<std::string> phase_names;
  for (const auto& p : data->cell->spec.phases)
    phase_names.push_back(p.name);
  const std::shared_ptr<const CellData> cell = data->cell;
  // the entry and its phase-map side file in one locked transaction, as the
  // program's; without the GIL, since the lock may wait on another process
  py::gil_scoped_release unlocked;
  library.add(std::move(m), overwrite, [cell, phase_names](const std::filesystem::path& h5) {
    micro::writePhaseMap(cell->cell, phase_names, h5);
  });
}

} // namespace lamina::python
