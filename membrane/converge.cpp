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

ConvergenceStudy runConvergence(const std::filesystem::path& path,
                                const std::vector<std::string>& overrides,
                                const MaterialSources& sources, int levels, int sample_every,
                                bool quiet) {
  LAMINA_CHECK(levels >= 3, "--levels must be >= 3 (two differences give one rate)");
  LAMINA_CHECK(sample_every >= 1, "sample_every must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  const toml::table base = loadCaseDocument(path, overrides);
  const Model coarse = buildModel(base, path, sources);
  if (coarse.mesh.source != "structured")
    throw Error("the convergence study needs mesh.type = \"rectangle\"",
                ErrorContext{path.string(), 0, "mesh.type"});
  const auto* mesh_tbl = base["mesh"].as_table();
  const int nx0 = static_cast<int>((*mesh_tbl)["nx"].value<std::int64_t>().value_or(0));
  const int ny0 = static_cast<int>(
      (*mesh_tbl)["ny"].value<std::int64_t>().value_or(static_cast<std::int64_t>(nx0)));
  const double dt0 = coarse.time.dt;
  const long steps0 = std::lround(coarse.time.t_end / dt0);
  const int nsample_nodes = coarse.mesh.numNodes();
  // The finest grid is refused up front, before the coarse ones ran: it has
  // 2^(levels-1) times the cells per direction and the steps.
  LAMINA_CHECK(levels <= 20,
               "--levels must be <= 20 (the finest grid has 2^(levels-1) times "
               "the cells per direction), got ",
               levels);
  const double f_max = std::ldexp(1.0, levels - 1);
  const ErrorContext levels_ctx{path.string(), 0, "--levels " + std::to_string(levels)};
  if (!(double(std::max(nx0, ny0)) * f_max <= 100000))
    throw Error("the finest grid would have nx = " + core::formatShort(nx0 * f_max) +
                    ", ny = " + core::formatShort(ny0 * f_max) +
                    "; mesh.nx and mesh.ny are at most "
                    "100000",
                levels_ctx);
  requireRunMemory((nx0 * f_max + 1) * (ny0 * f_max + 1), "the finest grid", levels_ctx);
  if (!(double(steps0) * f_max <= kMaxSteps))
    throw Error("the finest grid would take " + core::formatShort(double(steps0) * f_max) +
                    " steps; at most " + core::formatShort(kMaxSteps),
                levels_ctx);

  ConvergenceStudy study;
  std::vector<std::vector<double>> su(levels), sv(levels);
  for (int k = 0; k < levels; ++k) {
    const int f = 1 << k;
    toml::table doc = base;
    core::applyOverride(doc, "mesh.nx=" + std::to_string(nx0 * f));
    core::applyOverride(doc, "mesh.ny=" + std::to_string(ny0 * f));
    core::applyOverride(doc, "time.dt=" + core::formatExact(dt0 / f));
    const Model model = buildModel(doc, path, sources);
    study.nx.push_back(nx0 * f);
    study.dt.push_back(dt0 / f);
    std::vector<int> at(nsample_nodes);
    for (int i = 0; i < nsample_nodes; ++i)
      at[i] = model.mesh.nearestNode(coarse.mesh.nodes[i]);
    Simulation sim(model);
    core::ProgressLine progress("level " + std::to_string(k + 1) + "/" + std::to_string(levels),
                                steps0 * f, quiet);
    for (long s = 1; s <= steps0 * f; ++s) {
      sim.step();
      if (s % (static_cast<long>(f) * sample_every) != 0)
        continue;
      for (int i : at)
        for (int c = 0; c < 3; ++c) {
          su[k].push_back(sim.u()[3 * i + c]);
          sv[k].push_back(sim.v()[3 * i + c]);
        }
      progress.update(s);
    }
    progress.finish();
  }
  auto norms = [](const std::vector<double>& a, const std::vector<double>& b) {
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
  };
  for (int k = 1; k < levels; ++k) {
    study.du.push_back(norms(su[k], su[k - 1]));
    study.dv.push_back(norms(sv[k], sv[k - 1]));
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
  std::ostringstream os;
  os << "level  nx     dt            |u_k - u_k-1|: L1       L2           Linf"
        "         |v_k - v_k-1|: L1       L2           Linf\n";
  for (size_t k = 0; k < nx.size(); ++k) {
    os << k << "      " << nx[k] << "\t" << core::formatShort(dt[k], 4);
    if (k > 0) {
      for (double x : du[k - 1])
        os << "\t" << core::formatShort(x, 4);
      os << "\t";
      for (double x : dv[k - 1])
        os << "\t" << core::formatShort(x, 4);
    }
    os << "\n";
  }
  os << "observed rate         displacement: L1 " << core::formatShort(rate_u[0], 4) << "  L2 "
     << core::formatShort(rate_u[1], 4) << "  Linf " << core::formatShort(rate_u[2], 4) << "\n";
  os << "                      velocity:     L1 " << core::formatShort(rate_v[0], 4) << "  L2 "
     << core::formatShort(rate_v[1], 4) << "  Linf " << core::formatShort(rate_v[2], 4) << "\n";
  return os.str();
}

} // namespace lamina::membrane
