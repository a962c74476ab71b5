#include "homogenize/nonlinear_run.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/hdf5_file.hpp"
#include "core/interrupt.hpp"
#include "core/names.hpp"
#include "core/progress.hpp"
#include "homogenize/library_entry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <sstream>

namespace lamina::homogenize {

namespace {

constexpr const char* kComponents[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};

/// ",e_xx,...,e_xz,s_xx,...,s_xz"
std::string values(const materials::Vector6& e, const materials::Vector6& s) {
  std::string out;
  for (int a = 0; a < 6; ++a)
    out += "," + core::formatExact(e[a]);
  for (int a = 0; a < 6; ++a)
    out += "," + core::formatExact(s[a]);
  return out;
}

std::string row(double t, const materials::Vector6& e, const materials::Vector6& s) {
  return core::formatExact(t) + values(e, s);
}

std::filesystem::path beside(const std::filesystem::path& out, const std::string& suffix) {
  return out.parent_path() / (out.stem().string() + suffix);
}

/// Strain and stress fields of one step into the open HDF5 file.
void writeFields(core::H5File& f, int step, const Grid& g, const std::vector<double>& eps,
                 const std::vector<double>& sig) {
  const std::string group = "/step_" + std::to_string(step);
  f.createGroup(group);
  const std::vector<std::uint64_t> dims{static_cast<std::uint64_t>(g.n[0]),
                                        static_cast<std::uint64_t>(g.n[1]),
                                        static_cast<std::uint64_t>(g.n[2])};
  for (int a = 0; a < 6; ++a) {
    f.writeDoubles(group + "/eps_" + kComponents[a], eps.data() + a * g.size(), dims);
    f.writeDoubles(group + "/sig_" + kComponents[a], sig.data() + a * g.size(), dims);
  }
}

/// XDMF temporal collection of the written steps (ParaView).
std::string fieldsXdmf(const std::string& h5name, const Grid& g,
                       const std::vector<std::pair<int, double>>& steps) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"history\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& [step, t] : steps) {
    x << "   <Grid Name=\"step_" << step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << core::formatExact(t) << "\"/>\n"
      << "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << g.n[0] + 1 << " "
      << g.n[1] + 1 << " " << g.n[2] + 1 << "\"/>\n"
      << "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      << "     <DataItem Dimensions=\"3\" Format=\"XML\">0 0 0</DataItem>\n"
      << "     <DataItem Dimensions=\"3\" Format=\"XML\">" << core::formatExact(g.h[0]) << " "
      << core::formatExact(g.h[1]) << " " << core::formatExact(g.h[2]) << "</DataItem>\n"
      << "    </Geometry>\n";
    for (const char* kind : {"eps_", "sig_"})
      for (const char* c : kComponents)
        x << "    <Attribute Name=\"" << kind << c
          << "\" Center=\"Cell\" AttributeType=\"Scalar\">\n     <DataItem Dimensions=\"" << g.n[0]
          << " " << g.n[1] << " " << g.n[2]
          << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5name << ":/step_"
          << step << "/" << kind << c << "</DataItem>\n    </Attribute>\n";
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  return x.str();
}

} // namespace

std::vector<materials::LawPtr> phaseLaws(const micro::CellSpec& spec) {
  std::vector<materials::LawPtr> laws;
  for (const micro::Phase& p : spec.phases) {
    if (p.isVoid())
      throw Error("phase '" + p.name +
                      "' is void (a pore): nonlinear runs (--path, "
                      "--tangent-rates) take cells whose every phase has a stiffness; the linear "
                      "homogenization (no --path) handles pores",
                  {spec.file, 0, "phases.law"});
    laws.push_back(p.model);
  }
  return laws;
}

std::vector<std::filesystem::path> pathOutputs(const std::filesystem::path& out, bool fields) {
  if (out.empty())
    return {};
  std::vector<std::filesystem::path> files{out, beside(out, "-phases.csv")};
  if (fields) {
    files.push_back(beside(out, "-fields.h5"));
    files.push_back(beside(out, "-fields.xdmf"));
  }
  return files;
}

std::vector<StepResult> runPath(const micro::CellSpec& spec, const micro::UnitCell& cell,
                                const PathSpec& path, const NonlinearOptions& options,
                                const std::filesystem::path& out,
                                const std::vector<int>& field_steps,
                                const std::function<void(const StepResult&)>& report) {
  const MacroHistory history = pathHistory(path.path, path.rate, path.to, path.steps, path.unload);
  for (int s : field_steps)
    LAMINA_CHECK(s >= 1 && static_cast<std::size_t>(s) <= history.steps.size(), "field step ", s,
                 " is outside the history (1..", history.steps.size(), ")");
  for (const std::filesystem::path& f : pathOutputs(out, !field_steps.empty()))
    core::checkReplaceable(f, "--out"); // before the run, not after it
  NonlinearHomogenizer h(gridOf(cell), cell.phase.toVector(), phaseLaws(spec), options);
  std::unique_ptr<core::H5File> fields;
  const std::filesystem::path h5 = beside(out, "-fields.h5");
  // the fields are written aside and renamed into place with the CSVs: a
  // failed run replaces nothing
  const std::filesystem::path h5_tmp = h5.string() + ".tmp";
  struct RemoveAside {
    const std::filesystem::path& file;
    ~RemoveAside() {
      std::error_code ec;
      std::filesystem::remove(file, ec);
    }
  } remove_aside{h5_tmp};
  std::vector<std::pair<int, double>> written;
  if (!field_steps.empty()) {
    LAMINA_CHECK(!out.empty(), "fields need an output file (--out)");
    fields = std::make_unique<core::H5File>(h5_tmp, core::H5File::Mode::Create);
  }
  // the steps' progress goes to an observer only (the Python module's
  // callback): the program prints its own line per step
  core::ProgressLine progress("path steps", static_cast<long>(history.steps.size()), true);
  auto each = [&](const StepResult& r) {
    progress.update(r.step);
    if (fields && std::find(field_steps.begin(), field_steps.end(), r.step) != field_steps.end()) {
      writeFields(*fields, r.step, h.grid(), h.strainField(), h.stressField());
      written.emplace_back(r.step, r.t);
    }
    if (report)
      report(r);
    core::throwIfInterrupted("homogenization"); // a safe point between steps
  };
  const std::vector<StepResult> results = h.run(history, each);
  progress.finish();
  if (out.empty())
    return results;
  std::string csv = std::string(materials::kDriveHeader) + ",newton,krylov,residual,wall_s\n";
  csv += row(0, materials::Vector6::Zero(), materials::Vector6::Zero()) + ",0,0,0,0\n";
  for (const StepResult& r : results)
    csv += row(r.t, r.E, r.Sigma) + "," + std::to_string(r.newton) + "," +
           std::to_string(r.krylov) + "," + core::formatExact(r.residual) + "," +
           core::formatExact(r.wall_s) + "\n";
  core::writeFileAtomically(out, csv);
  std::string phases = "t,phase";
  for (const char* kind : {"eps_", "sig_"})
    for (const char* c : kComponents)
      phases += std::string(",") + kind + c;
  phases += "\n";
  for (const StepResult& r : results)
    for (std::size_t q = 0; q < r.phase_E.size(); ++q)
      phases += core::formatExact(r.t) + "," + spec.phases[q].name +
                values(r.phase_E[q], r.phase_S[q]) + "\n";
  core::writeFileAtomically(beside(out, "-phases.csv"), phases);
  if (fields) {
    fields.reset();
    core::renameIntoPlace(h5_tmp, h5);
    core::writeFileAtomically(beside(out, "-fields.xdmf"),
                              fieldsXdmf(h5.filename().string(), gridOf(cell), written));
  }
  return results;
}

std::string rateEntryName(const std::string& base, double rate) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", rate);
  return base + "-R" + buf;
}

std::vector<std::string> checkTangentSpec(const std::string& base, const TangentSpec& tangent,
                                          const materials::Library& library, bool overwrite) {
  if (tangent.rates.empty())
    throw Error("no rate given for the tangent entries", {"", 0, "--tangent-rates"});
  if (!(tangent.increment > 0 && tangent.increment <= 1)) // a strain increment
    throw Error("the tangent increment must be a strain in (0, 1]", {"", 0, "--tangent-increment"});
  if (tangent.strain > 0)
    materials::checkFinalStrain(tangent.path.path, tangent.strain, "--tangent-strain");
  else if (!(tangent.strain == 0))
    throw Error("the tangent strain must not be negative", {"", 0, "--tangent-strain"});
  std::vector<std::string> names;
  for (double rate : tangent.rates) {
    materials::checkRate(rate, "--tangent-rates", true);
    if (tangent.strain > 0 && !std::isfinite(rate))
      throw Error("an infinite rate reaches no strain: use --tangent-strain 0",
                  {"", 0, "--tangent-rates"});
    names.push_back(rateEntryName(base, rate));
    core::checkName(names.back(), "entry name", {"", 0, "--name"});
  }
  library.checkNewNames(names, overwrite, "--tangent-rates");
  return names;
}

void addTangentEntries(const micro::CellSpec& spec, const micro::UnitCell& cell,
                       const std::string& base, const TangentSpec& tangent,
                       const NonlinearOptions& options, materials::Library& library, bool overwrite,
                       const std::function<void(const materials::Material&)>& report) {
  checkTangentSpec(base, tangent, library, overwrite); // before anything is computed
  std::vector<materials::Library::Addition> additions;
  for (double rate : tangent.rates) {
    const auto t0 = std::chrono::steady_clock::now();
    NonlinearHomogenizer h(gridOf(cell), cell.phase.toVector(), phaseLaws(spec), options);
    int newton = 0, krylov = 0;
    if (tangent.strain > 0) {
      const MacroHistory hist =
          pathHistory(tangent.path.path, rate, tangent.strain, tangent.path.steps, false);
      for (const StepResult& r : h.run(hist)) {
        newton += r.newton;
        krylov += r.krylov;
      }
    }
    const double dt = std::isfinite(rate) ? tangent.increment / rate : 0.0;
    const materials::Matrix6 Ct = h.effectiveTangent(dt);
    materials::Material m;
    m.name = rateEntryName(base, rate);
    m.kind = "homogenized";
    const materials::Stiffness raw(Ct);
    m.C = raw.symmetrized();
    m.density = meanDensity(spec, cell);
    m.provenance = cellProvenance("homogenize (nonlinear: rate-dependent tangent)", spec, cell);
    toml::table& p = m.provenance;
    toml::array names;
    for (const auto& ph : spec.phases)
      names.push_back(ph.name + " (" + ph.source + ", " + materials::toString(ph.law) + ")");
    p.insert("phases", names);
    p.insert("rate", std::isfinite(rate) ? rate : std::numeric_limits<double>::infinity());
    p.insert("strain", tangent.strain);
    p.insert("path", materials::toString(tangent.path.path));
    p.insert("path_steps", tangent.path.steps);
    p.insert("increment", tangent.increment);
    p.insert("dt", dt);
    p.insert("definition", "d<sigma>/dE of a strain increment over dt = increment / rate from "
                           "the state reached along path at rate (per-voxel consistent tangents, "
                           "symmetrized, homogenized by six linear solves)");
    p.insert("solver", "Newton + FFT-preconditioned CG, rotated staggered grid (Willot 2015)");
    p.insert("tol", options.tol);
    p.insert("newton_iterations", newton);
    p.insert("krylov_iterations", krylov);
    p.insert("asymmetry_before_symmetrizing", raw.asymmetry());
    p.insert("wall_s",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    additions.push_back({std::move(m), {}});
  }
  library.add(additions, overwrite); // all entries in one transaction
  if (report)
    for (const auto& a : additions)
      report(a.material);
}

} // namespace lamina::homogenize
