#include "membrane/converge.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/progress.hpp"
#include "core/toml_reader.hpp"
#include "membrane/simulation.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

namespace lamina::membrane {

double observedRate(const std::vector<double>& e) {
  const int m = static_cast<int>(e.size());
  LAMINA_CHECK(m >= 1, "no differences to fit");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < m; ++k) {
    const double y = std::log2(std::max(e[k], 1e-300));
    sx += k;
    sy += y;
    sxx += double(k) * k;
    sxy += k * y;
  }
  if (m == 1)
    return 0.0;
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  return -slope;
}

namespace {

/// Level 0 of a study: the case as given.
struct CoarseGrid {
  int nx, ny;   ///< squares along x and y
  double dt;    ///< time step
  long steps;   ///< steps to t_end
  int nsamples; ///< nodes: every level is sampled at (the nodes nearest) these
};

/// Level 0's grid, of the case document @p base built as @p coarse; refuses
/// a mesh that is not a structured rectangle.
CoarseGrid coarseGrid(const toml::table& base, const Model& coarse,
                      const std::filesystem::path& path) {
  if (coarse.mesh.source != "structured")
    throw Error("the convergence study needs mesh.type = \"rectangle\"",
                ErrorContext{path.string(), 0, "mesh.type"});
  const auto* mesh_tbl = base["mesh"].as_table();
  CoarseGrid g;
  g.nx = static_cast<int>((*mesh_tbl)["nx"].value<std::int64_t>().value_or(0));
  g.ny = static_cast<int>(
      (*mesh_tbl)["ny"].value<std::int64_t>().value_or(static_cast<std::int64_t>(g.nx)));
  g.dt = coarse.time.dt;
  g.steps = std::lround(coarse.time.t_end / g.dt);
  g.nsamples = coarse.mesh.numNodes();
  return g;
}

/// Refuses the finest grid up front, before the coarse ones ran: it has
/// 2^(levels-1) times the cells per direction and the steps.
void checkFinestGrid(const CoarseGrid& g, int levels, const std::filesystem::path& path) {
  LAMINA_CHECK(levels <= 20,
               "--levels must be <= 20 (the finest grid has 2^(levels-1) times "
               "the cells per direction), got ",
               levels);
  const double f_max = std::ldexp(1.0, levels - 1);
  const ErrorContext levels_ctx{path.string(), 0, "--levels " + std::to_string(levels)};
  if (!(double(std::max(g.nx, g.ny)) * f_max <= 100000))
    throw Error("the finest grid would have nx = " + core::formatShort(g.nx * f_max) +
                    ", ny = " + core::formatShort(g.ny * f_max) +
                    "; mesh.nx and mesh.ny are at most "
                    "100000",
                levels_ctx);
  requireRunMemory((g.nx * f_max + 1) * (g.ny * f_max + 1), "the finest grid", levels_ctx);
  if (!(double(g.steps) * f_max <= kMaxSteps))
    throw Error("the finest grid would take " + core::formatShort(double(g.steps) * f_max) +
                    " steps; at most " + core::formatShort(kMaxSteps),
                levels_ctx);
}

/// The case every level of a study refines.
struct StudyCase {
  const toml::table& base;
  const std::filesystem::path& path;
  const MaterialSources& sources;
  const Model& coarse; ///< level 0, whose nodes are sampled
  CoarseGrid grid;
};

/// The displacements and velocities of one level at the sample nodes and times.
struct LevelSamples {
  std::vector<double> u, v;
};

/// The model of level @p k: 2^k times the squares per direction, tau / 2^k.
Model levelModel(const StudyCase& c, int k) {
  const int f = 1 << k;
  toml::table doc = c.base;
  core::applyOverride(doc, "mesh.nx=" + std::to_string(c.grid.nx * f));
  core::applyOverride(doc, "mesh.ny=" + std::to_string(c.grid.ny * f));
  core::applyOverride(doc, "time.dt=" + core::formatExact(c.grid.dt / f));
  return buildModel(doc, c.path, c.sources);
}

/// Runs level @p k of @p levels, sampled every @p sample_every coarse steps.
LevelSamples runLevel(const StudyCase& c, int k, int levels, int sample_every, bool quiet) {
  const int f = 1 << k;
  const Model model = levelModel(c, k);
  std::vector<int> at(c.grid.nsamples);
  for (int i = 0; i < c.grid.nsamples; ++i)
    at[i] = model.mesh.nearestNode(c.coarse.mesh.nodes[i]);
  Simulation sim(model);
  core::ProgressLine progress("level " + std::to_string(k + 1) + "/" + std::to_string(levels),
                              c.grid.steps * f, quiet);
  LevelSamples samples;
  for (long s = 1; s <= c.grid.steps * f; ++s) {
    sim.step();
    if (s % (static_cast<long>(f) * sample_every) != 0)
      continue;
    for (int i : at)
      for (int d = 0; d < 3; ++d) {
        samples.u.push_back(sim.u()[3 * i + d]);
        samples.v.push_back(sim.v()[3 * i + d]);
      }
    progress.update(s);
  }
  progress.finish();
  return samples;
}

/// L1 (mean), L2 (root mean square) and Linf of a - b.
std::array<double, 3> differenceNorms(const std::vector<double>& a, const std::vector<double>& b) {
  std::array<double, 3> r{0, 0, 0};
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = std::abs(a[i] - b[i]);
    r[0] += d;
    r[1] += d * d;
    r[2] = std::max(r[2], d);
  }
  r[0] /= double(a.size());
  r[1] = std::sqrt(r[1] / double(a.size()));
  return r;
}

/// The differences between consecutive levels and their observed rates.
void compareLevels(const std::vector<LevelSamples>& levels, ConvergenceStudy& study) {
  for (size_t k = 1; k < levels.size(); ++k) {
    study.du.push_back(differenceNorms(levels[k].u, levels[k - 1].u));
    study.dv.push_back(differenceNorms(levels[k].v, levels[k - 1].v));
  }
  for (int j = 0; j < 3; ++j) {
    std::vector<double> eu, ev;
    for (size_t k = 0; k < study.du.size(); ++k) {
      eu.push_back(study.du[k][j]);
      ev.push_back(study.dv[k][j]);
    }
    study.rate_u[j] = observedRate(eu);
    study.rate_v[j] = observedRate(ev);
  }
}

} // namespace

ConvergenceStudy runConvergence(const std::filesystem::path& path,
                                const std::vector<std::string>& overrides,
                                const MaterialSources& sources, int levels, int sample_every,
                                bool quiet) {
  LAMINA_CHECK(levels >= 3, "--levels must be >= 3 (two differences give one rate)");
  LAMINA_CHECK(sample_every >= 1, "sample_every must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  const toml::table base = loadCaseDocument(path, overrides);
  const Model coarse = buildModel(base, path, sources);
  const CoarseGrid grid = coarseGrid(base, coarse, path);
  checkFinestGrid(grid, levels, path);
  const StudyCase study_case{base, path, sources, coarse, grid};
  ConvergenceStudy study;
  std::vector<LevelSamples> samples;
  for (int k = 0; k < levels; ++k) {
    const int f = 1 << k;
    study.nx.push_back(grid.nx * f);
    study.dt.push_back(grid.dt / f);
    samples.push_back(runLevel(study_case, k, levels, sample_every, quiet));
  }
  compareLevels(samples, study);
  study.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return study;
}

nlohmann::json ConvergenceStudy::toJson() const {
  nlohmann::json j;
  j["nx"] = nx;
  j["dt"] = dt;
  auto arr = [](const std::vector<std::array<double, 3>>& d) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& x : d)
      a.push_back({{"L1", x[0]}, {"L2", x[1]}, {"Linf", x[2]}});
    return a;
  };
  j["displacement_differences"] = arr(du);
  j["velocity_differences"] = arr(dv);
  j["rates"] = {{"displacement", {{"L1", rate_u[0]}, {"L2", rate_u[1]}, {"Linf", rate_u[2]}}},
                {"velocity", {{"L1", rate_v[0]}, {"L2", rate_v[1]}, {"Linf", rate_v[2]}}}};
  j["wall_s"] = wall_s;
  return j;
}

std::string ConvergenceStudy::toTable() const {
  // One table, every column of a fixed width and left-aligned, so that a
  // value starts where its header does; the last row holds the rates.
  static constexpr std::size_t kWidths[] = {7, 7, 11, 11, 11, 11, 11, 11, 11};
  std::ostringstream os;
  const auto row = [&os](const std::vector<std::string>& cells) {
    std::string line;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      line += cells[c];
      if (c + 1 < cells.size()) // at least one space between columns
        line += std::string(cells[c].size() < kWidths[c] ? kWidths[c] - cells[c].size() : 1, ' ');
    }
    os << line << "\n";
  };
  const auto num = [](double x) { return core::formatShort(x, 4); };
  os << "du, dv: norms of u_k - u_k-1 and v_k - v_k-1 at the level-0 samples; "
        "rate: the observed order\n";
  row({"level", "nx", "dt (s)", "du L1", "du L2", "du Linf", "dv L1", "dv L2", "dv Linf"});
  for (std::size_t k = 0; k < nx.size(); ++k) {
    std::vector<std::string> cells = {std::to_string(k), std::to_string(nx[k]), num(dt[k])};
    for (const auto* d : {&du, &dv})
      for (int j = 0; j < 3; ++j)
        cells.push_back(k > 0 ? num((*d)[k - 1][static_cast<std::size_t>(j)]) : "-");
    row(cells);
  }
  std::vector<std::string> rates = {"rate", "", ""};
  for (const auto* r : {&rate_u, &rate_v})
    for (double x : *r)
      rates.push_back(num(x));
  row(rates);
  return os.str();
}

} // namespace lamina::membrane
