#include "homogenize/reduced_order_run.hpp"

#include "materials/reduced_order_law.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/resources.hpp"
#include "homogenize/library_entry.hpp"
#include "materials/export.hpp"

#include <cstdio>
#include <sstream>

namespace lamina::homogenize {

namespace {

const char* methodName(PartitionMethod m) {
  return m == PartitionMethod::KMeans ? "k-means" : "phase";
}

} // namespace

std::vector<materials::ReducedOrderPhase> reducedOrderPhases(const micro::CellSpec& spec) {
  std::vector<materials::ReducedOrderPhase> phases;
  for (const micro::Phase& p : spec.phases)
    phases.push_back({p.name, p.lawSpec(), p.density});
  return phases;
}

void checkReducible(const micro::CellSpec& spec, const micro::UnitCell& cell) {
  for (const micro::Phase& ph : spec.phases)
    if (ph.isVoid())
      throw Error("phase '" + ph.name +
                      "' is void (a pore): a reduced-order cell takes cells "
                      "whose every phase has a stiffness",
                  {spec.file, 0, "phases.law"});
  for (const micro::Phase& ph : spec.phases)
    if (!ph.J.empty() && !(ph.J.size() == 1 && ph.J[0] == 1.0))
      throw Error("phase '" + ph.name +
                      "' lists gvbo states J: a reduced-order cell takes "
                      "every phase at J = 1 (its law then follows J at every point); remove J",
                  {spec.file, 0, "phases.J"});
  if (cell.oriented.empty())
    return;
  const micro::OrientedVoxel& v = cell.oriented.front();
  throw Error("a reduced-order cell needs one stiffness per phase, but phase '" +
                  spec.phases[static_cast<std::size_t>(v.phase)].name + "' follows its yarn's " +
                  "path (" + std::to_string(cell.oriented.size()) +
                  " voxels rotated one by one); reduce a cell without oriented yarns",
              {spec.file, 0, ""});
}

ReducedOrderResult buildReducedOrder(const micro::CellSpec& spec, const micro::UnitCell& cell,
                                     const ReducedOrderOptions& options) {
  checkReducible(spec, cell);
  ReducedOrderBuilder builder(gridOf(cell), cell.phase.toVector(), reducedOrderPhases(spec),
                              spec.physical_size, options);
  return builder.run();
}

int stateDoublesPerPoint(const materials::ReducedOrderModel& m) {
  return materials::ReducedOrderLaw("", m).stateSize(); // the law's own layout
}

materials::Material makeReducedOrderEntry(const std::string& name, const micro::CellSpec& spec,
                                          const micro::UnitCell& cell,
                                          const ReducedOrderResult& result,
                                          const ReducedOrderOptions& options) {
  const materials::ReducedOrderModel& model = result.model;
  materials::Material m;
  m.name = name;
  m.kind = materials::kReducedOrderKind;
  m.C = materials::Stiffness(model.C);
  m.density = model.density;
  m.phases = model.phases;
  m.provenance = cellProvenance("homogenize (reduced-order cell)", spec, cell);
  toml::table& p = m.provenance;
  p.insert("voxels", static_cast<std::int64_t>(cell.voxels()));
  toml::array sources, per_phase;
  for (const auto& ph : spec.phases)
    sources.push_back(ph.name + " (" + ph.source + ", " + materials::toString(ph.law) + ")");
  p.insert("phase_sources", sources);
  p.insert("phase_map", "plain: each voxel its centre's phase (composite voxels do not enter)");
  p.insert("partitions", model.partitions());
  for (int k : model.partitionsPerPhase())
    per_phase.push_back(k);
  p.insert("partitions_per_phase", per_phase);
  p.insert("partition_method", methodName(options.partitions.method));
  if (options.partitions.method == PartitionMethod::KMeans) {
    p.insert("partition_seed", static_cast<std::int64_t>(options.partitions.seed));
    toml::array lloyd;
    for (int it : result.partitions.iterations)
      lloyd.push_back(it);
    p.insert("lloyd_iterations", lloyd);
  }
  p.insert("reference_stiffness", "each phase's law at J = 1 (elasticStiffness(1.0))");
  p.insert("scheme", materials::toString(model.scheme));
  p.insert("solver", kSolverName);
  p.insert("tol", options.tol);
  p.insert("solves", result.cost.solves);
  p.insert("iterations", static_cast<std::int64_t>(result.cost.iterations));
  p.insert("residual", result.cost.max_residual);
  p.insert("asymmetry_before_symmetrizing", result.linear.asymmetry);
  p.insert("reference_lambda0", result.linear.lambda0);
  p.insert("reference_mu0", result.linear.mu0);
  p.insert("wall_s", result.cost.wall_s);
  p.insert("peak_memory_bytes", result.cost.peak_bytes);
  if (result.dispersion) {
    m.dispersion = result.dispersion->D;
    m.cell_size = cell.size;
    p.insert("dispersion_method", kDispersionMethod);
    toml::array ls;
    for (double r : result.dispersion->residual)
      ls.push_back(r);
    p.insert("dispersion_residuals", ls);
  }
  return m;
}

ReducedOrderResult addReducedOrderEntry(const micro::CellSpec& spec, const micro::UnitCell& cell,
                                        const std::string& name, const ReducedOrderOptions& options,
                                        materials::Library& library, bool overwrite) {
  library.checkNewNames({name}, overwrite, "--name"); // before anything is computed
  ReducedOrderResult result = buildReducedOrder(spec, cell, options);
  const materials::ReducedOrderModel& model = result.model;
  library.add(
      makeReducedOrderEntry(name, spec, cell, result, options), overwrite,
      [&model](const std::filesystem::path& h5) { materials::writeReducedOrderArrays(h5, model); });
  return result;
}

nlohmann::json reducedOrderJson(const std::string& name, const ReducedOrderResult& result,
                                const std::filesystem::path& library) {
  const materials::ReducedOrderModel& m = result.model;
  nlohmann::json j;
  j["name"] = name;
  j["library"] = libraryJsonPath(library);
  j["partitions"] = m.partitions();
  j["partition_phase"] = m.partition_phase;
  j["fractions"] = m.fraction;
  nlohmann::json per_phase = nlohmann::json::object();
  const std::vector<int> count = m.partitionsPerPhase();
  for (std::size_t p = 0; p < m.phases.size(); ++p)
    per_phase[m.phases[p].name] = count[p];
  j["partitions_per_phase"] = per_phase;
  j["C"] = materials::matrixToJson(m.C);
  j["density"] = m.density;
  if (result.dispersion)
    j["dispersion"] = materials::matrixToJson(m.D_lin);
  j["solves"] = result.cost.solves;
  j["iterations"] = result.cost.iterations;
  j["residual"] = result.cost.max_residual;
  j["wall_s"] = result.cost.wall_s;
  j["peak_memory_bytes"] = result.cost.peak_bytes;
  j["influence_doubles"] = result.cost.influence_doubles;
  j["state_doubles_per_point"] = stateDoublesPerPoint(m);
  return j;
}

std::string reducedOrderSummary(const std::string& name, const ReducedOrderResult& result) {
  const materials::ReducedOrderModel& m = result.model;
  const ReducedOrderCost& c = result.cost;
  std::ostringstream os;
  os << name << ": reduced-order cell of " << m.partitions() << " partitions (";
  const std::vector<int> count = m.partitionsPerPhase();
  for (std::size_t p = 0; p < m.phases.size(); ++p)
    os << (p ? ", " : "") << m.phases[p].name << " " << count[p];
  os << "), density " << core::formatShort(m.density) << " kg/m^3\n";
  os << "solves " << c.solves << ", CG iterations " << c.iterations << ", largest residual "
     << core::formatShort(c.max_residual, 3) << ", wall " << core::formatShort(c.wall_s, 3)
     << " s, peak memory " << core::formatBytes(c.peak_bytes) << " (influence spectra "
     << core::formatBytes(8 * c.influence_doubles) << ")\n";
  os << "state doubles per point " << stateDoublesPerPoint(m)
     << (result.dispersion ? ""
                           : "; no micro-inertia: the cell has no size in metres ([cell] size)")
     << "\n";
  return os.str();
}

} // namespace lamina::homogenize
