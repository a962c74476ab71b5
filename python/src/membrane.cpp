/// @file membrane.cpp
/// @brief Python bindings: see common.hpp (bindMembrane) and python/lamina/__init__.pyi.
///
/// The C++ half of lamina.membrane.run (python/lamina/membrane.py reads the
/// outputs back): _membrane_run does what `membrane run CASE --out DIR
/// --quiet` does, on a case file or on a dict with a case file's keys;
/// _read_h5 reads one dataset of a field file (so that no h5py is needed);
/// blast is `membrane blast --json`.
#include "core/atomic_file.hpp"
#include "core/checksum.hpp"
#include "core/hdf5_file.hpp"
#include "core/parallel.hpp"
#include "core/resources.hpp"
#include "core/toml_reader.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/io/checkpoint.hpp"
#include "membrane/loads/blast.hpp"
#include "membrane/run.hpp"
#include "python/src/common.hpp"
#include "python/src/convert.hpp"

#include <pybind11/numpy.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

namespace lamina::python {

namespace {

/// The file name a dict case's errors name (it is no file: relative paths in
/// the dict resolve against the working folder, the parent of this name).
constexpr const char* kDictCase = "<dict>";

/// A case ready to run: its model and the digest its checkpoints carry.
struct PreparedCase {
  membrane::Model model;
  std::string digest;
  std::filesystem::path path; ///< the case file ("<dict>" for a dict)
};

/// @return the case @p case_obj (a path or a dict) read with the --set
/// assignments @p overrides, as `membrane run` reads a case file.
PreparedCase prepareCase(py::handle case_obj, const std::vector<std::string>& overrides) {
  const membrane::MaterialSources sources{}; // $LAMINA_LIBRARY, $LAMINA_CATALOG, defaults
  PreparedCase c;
  if (py::isinstance<py::dict>(case_obj)) {
    toml::table doc = toToml(case_obj, "");
    for (const auto& o : overrides)
      core::applyOverride(doc, o);
    if (!doc.contains("name")) // the program's default is the file's stem
      doc.insert("name", "case");
    c.path = kDictCase;
    std::ostringstream text;
    text << doc;
    core::Fnv1a f;
    f.add(text.str());
    c.digest = f.hex();
    c.model = membrane::buildModel(doc, c.path, sources);
    return c;
  }
  py::object path;
  try {
    path = py::module_::import("os").attr("fspath")(case_obj);
  } catch (py::error_already_set&) {
    throwInput("case must be a case file's path (str or os.PathLike) or a dict of its keys, got " +
                   typeName(case_obj),
               "case");
  }
  if (!py::isinstance<py::str>(path))
    throwInput("case must be a str path (bytes paths are not accepted)", "case");
  c.path = path.cast<std::string>();
  c.model = membrane::readCase(c.path, overrides, sources);
  c.digest = membrane::caseDigest(c.path, overrides);
  return c;
}

/// `membrane run`'s checks of its output folder (a folder or new, and not
/// one of the run's inputs).
void checkOutputFolder(const std::filesystem::path& out, const std::filesystem::path& case_path) {
  std::error_code ec;
  if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec))
    throw Error("the output folder exists and is not a directory; refusing to replace it",
                {out.string(), 0, "out"});
  std::vector<std::filesystem::path> inputs;
  if (case_path != kDictCase)
    inputs.push_back(case_path);
  core::checkOutputIsNotInput(out, inputs, "out");
}

/// _membrane_run(case, set, out, threads, progress) -> summary dict.
py::object membraneRun(hint::Case case_obj, hint::Overrides set, const std::string& out,
                       hint::OptionalInt threads_obj, hint::Progress progress) {
  const std::vector<std::string> overrides = toOverrides(set);
  int threads = 0;
  if (!threads_obj.is_none()) {
    if (!PyLong_Check(threads_obj.ptr()) || py::isinstance<py::bool_>(threads_obj))
      throwInput("threads must be an int or None", "threads");
    threads = threads_obj.cast<int>();
    core::checkThreads(threads, "threads");
  }
  LongCall call(std::move(progress));
  const PreparedCase c = prepareCase(case_obj, overrides);
  checkOutputFolder(out, c.path);
  membrane::RunOptions opt;
  opt.out_dir = out;
  opt.quiet = true;
  opt.case_digest = c.digest;
  nlohmann::json summary;
  call.run([&] {
    std::optional<core::ThreadsScope> scope;
    if (threads > 0)
      scope.emplace(threads);
    summary = membrane::runCase(c.model, opt);
  });
  return toPython(summary);
}

/// _read_h5(path, dataset) -> numpy array of float64 with the dataset's shape.
py::array_t<double> readH5(const std::string& path, const std::string& dataset) {
  if (!std::filesystem::exists(path))
    throw Error("field file not found", {path, 0, ""});
  const core::H5File file(path, core::H5File::Mode::ReadOnly);
  std::vector<std::uint64_t> dims;
  std::vector<double> values = file.readDoubles(dataset, dims);
  std::vector<py::ssize_t> shape(dims.begin(), dims.end());
  py::array_t<double> a(shape);
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

/// blast(charge, distance, burst) -> `membrane blast --json`'s object.
py::object blast(hint::Float charge, hint::Float distance, const std::string& burst_name) {
  // the library refuses non-positive and non-finite values with its own
  // messages; the conversion only refuses what is no number
  const double w = toDouble(charge, "charge", /*finite=*/false);
  const double r = toDouble(distance, "distance", /*finite=*/false);
  const auto burst = membrane::parseBurst(burst_name, {"", 0, "burst"});
  return toPython(membrane::blastToJson(membrane::kingeryBulmash(w, r, burst), burst));
}

} // namespace

void bindMembrane(py::module_& m) {
  m.def("_membrane_run", &membraneRun, py::arg("case"), py::arg("set"), py::arg("out"),
        py::arg("threads"), py::arg("progress"),
        "The computation of `membrane run CASE --out OUT --quiet` (lamina.membrane.run "
        "reads the outputs back); returns summary.json as a dict.");
  m.def("_read_h5", &readH5, py::arg("path"), py::arg("dataset"),
        "One dataset of doubles of an HDF5 file (a field file) as a float64 array.");
  m.def("blast", &blast, py::arg("charge"), py::arg("distance"), py::arg("burst") = "hemispherical",
        "Kingery-Bulmash parameters (`membrane blast --json`): charge in kg TNT,\n"
        "distance in m. The program's JSON object: the six parameters (floats, SI)\n"
        "and the inputs, burst, validity range and decay constants.");
}

} // namespace lamina::python
