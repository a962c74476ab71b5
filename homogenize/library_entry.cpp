#include "homogenize/library_entry.hpp"

#include "materials/export.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/phase_map_io.hpp"

#include "core/error.hpp"
#include "core/names.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#ifndef LAMINA_VERSION
#define LAMINA_VERSION "unknown"
#endif

namespace lamina::homogenize {

Grid gridOf(const micro::UnitCell& cell) {
  Grid g;
  g.n = cell.n;
  for (int d = 0; d < 3; ++d)
    g.h[static_cast<std::size_t>(d)] = cell.size[d] / cell.n[static_cast<std::size_t>(d)];
  return g;
}

std::string entryName(const std::string& base, double J, bool sweep) {
  if (!sweep)
    return base;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s-J%g", base.c_str(), J);
  return buf;
}

std::string utcNow() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

toml::table cellProvenance(const std::string& program, const micro::CellSpec& spec,
                           const micro::UnitCell& cell) {
  toml::table p;
  p.insert("program", program);
  p.insert("version", LAMINA_VERSION);
  p.insert("time", utcNow());
  p.insert("cell_file", spec.file);
  p.insert("cell_text", spec.text);
  if (!spec.overrides.empty()) { // --set KEY=VALUE over cell_text
    toml::array overrides;
    for (const auto& o : spec.overrides)
      overrides.push_back(o);
    p.insert("cell_overrides", std::move(overrides));
  }
  p.insert("resolution", toml::array{cell.n[0], cell.n[1], cell.n[2]});
  return p;
}

double meanDensity(const micro::CellSpec& spec, const micro::UnitCell& cell) {
  LAMINA_CHECK(cell.voxel_fraction.size() == spec.phases.size(), "the cell has ",
               cell.voxel_fraction.size(), " phase fractions for ", spec.phases.size(), " phases");
  double density = 0;
  for (std::size_t q = 0; q < spec.phases.size(); ++q)
    density += cell.voxel_fraction[q] * spec.phases[q].density;
  return density;
}

materials::Material makeEntry(const std::string& name, const micro::CellSpec& spec,
                              const micro::UnitCell& cell, const Result& result,
                              const Options& options, double J, const Dispersion* dispersion) {
  materials::Material m;
  m.name = name;
  m.C = result.C;
  m.density = meanDensity(spec, cell);
  m.kind = "homogenized";
  m.provenance = cellProvenance("homogenize", spec, cell);
  toml::table& p = m.provenance;
  p.insert("voxels", static_cast<std::int64_t>(result.voxels));
  toml::array fractions;
  for (double f : result.voxel_fraction)
    fractions.push_back(f);
  p.insert("volume_fractions", fractions);
  toml::array names;
  for (const auto& ph : spec.phases)
    names.push_back(ph.name + " (" + ph.source + ")");
  p.insert("phases", names);
  // per-voxel stiffnesses the solver holds besides the phases' (a composite
  // voxel's laminate; a whole voxel of a yarn following its path)
  p.insert("composite_voxels", static_cast<std::int64_t>(cell.composites.size()));
  p.insert("oriented_voxels", static_cast<std::int64_t>(cell.oriented.size()));
  p.insert("J", J);
  p.insert("solver", kSolverName);
  p.insert("tol", options.tol);
  p.insert("residual", result.maxResidual());
  toml::array its;
  for (int it : result.iterations())
    its.push_back(it);
  p.insert("iterations", its);
  toml::array residuals;
  for (const auto& c : result.cases)
    residuals.push_back(c.residual);
  p.insert("residuals", residuals);
  p.insert("asymmetry_before_symmetrizing", result.asymmetry);
  p.insert("symmetry", materials::toString(result.symmetry.cls));
  p.insert("reference_lambda0", result.lambda0);
  p.insert("reference_mu0", result.mu0);
  p.insert("wall_s", result.wall_s);
  if (dispersion) {
    m.dispersion = dispersion->D;
    m.cell_size = cell.size;
    p.insert("dispersion_method", kDispersionMethod);
    toml::array ls;
    for (double r : dispersion->residual)
      ls.push_back(r);
    p.insert("dispersion_residuals", ls);
  }
  return m;
}

namespace {

/// Refuses a cell with a size (its entry gets the dispersion tensor) and a
/// void phase: eq. 39 takes the displacement fluctuation of every voxel, and
/// inside a pore the cell problem leaves it undetermined.
void checkDispersion(const micro::CellSpec& spec) {
  if (!spec.physical_size)
    return;
  for (const micro::Phase& p : spec.phases)
    if (p.isVoid())
      throw Error("phase '" + p.name +
                      "' is void (a pore) and the cell has a size: the "
                      "dispersion tensor (micro-inertia) needs the displacement in every voxel, "
                      "which a pore leaves undetermined; leave size out for a porous cell",
                  {spec.file, 0, "cell.size"});
}

} // namespace

void checkPercolates(const micro::CellSpec& spec, const materials::Stiffness& C) {
  for (const micro::Phase& p : spec.phases)
    if (p.isVoid() && !C.valid())
      throw Error("the effective stiffness is singular: phase '" + p.name +
                      "' is void and the solid phases do not hold the cell together in every "
                      "direction",
                  {spec.file, 0, "phases"});
}

EntryResult homogenizeCell(const micro::CellSpec& spec, const micro::UnitCell& cell,
                           const std::string& name, double J, const Options& options,
                           const Distribution* dist) {
  checkDispersion(spec);
  EntryResult e{name, J, {}, std::nullopt};
  const Grid grid = gridOf(cell);
  const Distribution serial = Distribution::serial(grid);
  const Distribution& d = dist ? *dist : serial;
  const std::vector<double> density = spec.densities();
  // composite voxels (if any) enter as one laminate stiffness each; rank 0
  // builds them and every rank gets the stiffness list and its slab
  micro::VoxelMaterials vm;
  if (d.rank() == 0)
    vm = micro::voxelMaterials(cell, spec.stiffnessesAt(J), density);
  if (d.distributed()) {
    std::vector<double> packed;
    for (std::size_t m = 0; m < vm.C.size(); ++m) {
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
          packed.push_back(vm.C[m](i, j));
      packed.push_back(vm.density[m]);
    }
    d.broadcast(packed);
    vm.C.clear();
    vm.density.clear();
    for (std::size_t at = 0; at + 37 <= packed.size(); at += 37) {
      materials::Matrix6 c;
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
          c(i, j) = packed[at + 6 * static_cast<std::size_t>(i) + static_cast<std::size_t>(j)];
      vm.C.emplace_back(c);
      vm.density.push_back(packed[at + 36]);
    }
    vm.phase = d.scatter(vm.phase);
  }
  Homogenizer h(grid, d, std::move(vm.phase), std::move(vm.C), std::move(vm.density), options);
  // the dispersion tensor is accumulated on rank 0 from the gathered fields
  std::optional<DispersionAccumulator> acc;
  if (spec.physical_size && d.rank() == 0)
    acc.emplace(grid, cell.phase.toVector(), density); // read in the constructor only
  if (spec.physical_size)
    h.setDisplacementSink([&](int k, const double* u) {
      if (!d.distributed()) {
        acc->addLoadCase(k, u);
        return;
      }
      const std::vector<double> global = d.gather(u, 3);
      if (acc)
        acc->addLoadCase(k, global.data());
    });
  e.result = h.run();
  e.result.voxel_fraction = cell.voxel_fraction; // per phase, cut voxels split by fraction
  if (acc)
    e.dispersion = acc->result();
  return e;
}

std::vector<EntryResult>
homogenizeIntoLibrary(const micro::CellSpec& spec, const micro::UnitCell& cell,
                      const std::string& base, const Options& options, materials::Library& library,
                      bool overwrite, const std::function<void(const EntryResult&)>& report,
                      const Distribution* dist) {
  const Grid grid = gridOf(cell);
  const Distribution serial = Distribution::serial(grid);
  const Distribution& d = dist ? *dist : serial;
  const std::vector<double> states = spec.sweepStates();
  bool sweep = false;
  for (const auto& ph : spec.phases)
    sweep = sweep || ph.J.size() > 1;
  // every name checked before anything is computed: the entries of a sweep
  // are added all or none
  std::vector<std::string> entry_names;
  for (double J : states) {
    entry_names.push_back(entryName(base, J, sweep));
    core::checkName(entry_names.back(), "entry name", {"", 0, "--name"});
  }
  library.checkNewNames(entry_names, overwrite, "--name");
  std::vector<EntryResult> out;
  std::vector<materials::Library::Addition> additions;
  std::vector<std::string> phase_names;
  for (const auto& ph : spec.phases)
    phase_names.push_back(ph.name);
  for (std::size_t s = 0; s < states.size(); ++s) {
    const double J = states[s];
    EntryResult e = homogenizeCell(spec, cell, entry_names[s], J, options, &d);
    checkPercolates(spec, e.result.C); // a library entry's C is positive definite
    if (d.rank() == 0)                 // one writer
      // The phase map goes to an HDF5 side file beside the library (DESIGN.md:
      // large arrays never enter the text file), written in the same
      // transaction as the entry that names it: an entry never points at a
      // missing file and a failed add leaves no side file behind.
      additions.push_back({makeEntry(e.name, spec, cell, e.result, options, J,
                                     e.dispersion ? &*e.dispersion : nullptr),
                           [&cell, &phase_names](const std::filesystem::path& h5) {
                             micro::writePhaseMap(cell, phase_names, h5);
                           }});
    out.push_back(std::move(e));
  }
  if (d.rank() != 0)
    return out;
  library.add(std::move(additions), overwrite); // all entries in one transaction
  if (report)
    for (const EntryResult& e : out)
      report(e);
  return out;
}

std::string libraryJsonPath(const std::filesystem::path& library) {
  return std::filesystem::absolute(library).lexically_normal().string();
}

nlohmann::json toJson(const EntryResult& e, const std::filesystem::path& library) {
  const Result& r = e.result;
  nlohmann::json j;
  j["name"] = e.name;
  j["library"] = libraryJsonPath(library);
  j["C"] = materials::matrixToJson(r.C.matrix());
  j["density"] = r.density;
  j["iterations"] = r.iterations();
  j["residual"] = r.maxResidual();
  nlohmann::json residuals = nlohmann::json::array();
  for (const auto& c : r.cases)
    residuals.push_back(c.residual);
  j["residuals"] = residuals;
  j["voxels"] = r.voxels;
  j["volume_fraction"] = 1.0 - r.voxel_fraction.at(0); // all inclusions (voxels)
  j["phase_fractions"] = r.voxel_fraction;
  j["asymmetry"] = r.asymmetry;
  j["symmetry"] = materials::toString(r.symmetry.cls);
  j["J"] = e.J;
  j["wall_s"] = r.wall_s;
  if (e.dispersion) {
    j["dispersion"] = materials::matrixToJson(e.dispersion->D);
    j["dispersion_residuals"] = e.dispersion->residual;
  }
  return j;
}

} // namespace lamina::homogenize
