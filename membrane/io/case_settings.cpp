/// @file case_settings.cpp
/// @brief [time], [solver], [output] and [[probe]] of a case.

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lamina::membrane::case_io {

namespace {
/// Optional integer key @p key of @p t in [@p lo, INT_MAX] with a default:
/// read as 64 bits, so a value beyond an int is refused, never wrapped.
int intIn(const core::TableReader& t, std::string_view key, int lo, int fallback) {
  return static_cast<int>(t.getIntIn(key, lo, std::numeric_limits<int>::max(), fallback));
}
/// The keys of [time] that one scheme reads and the other would ignore.
const std::vector<const char*>& schemeOnlyKeys(IntegratorKind scheme) {
  static const std::vector<const char*> expl{"safety", "damping"};
  static const std::vector<const char*> newmark{"beta1", "beta2", "hht_alpha", "mass"};
  return scheme == IntegratorKind::Explicit ? expl : newmark;
}

/// Refuses the keys (of [time] @p t, and the [solver] table of @p root)
/// that only the scheme other than @p scheme reads, naming the key and the
/// scheme: a setting the run would ignore is an error, never a silence.
void refuseOtherSchemeKeys(const core::TableReader& root, const core::TableReader& t,
                           IntegratorKind scheme) {
  const bool expl = scheme == IntegratorKind::Explicit;
  const std::string why = std::string(" applies to the ") + (expl ? "Newmark" : "explicit") +
                          " scheme only; this case's time.integrator is \"" +
                          std::string(kIntegratorKindNames.name(scheme)) + "\"";
  const IntegratorKind other = expl ? IntegratorKind::Newmark : IntegratorKind::Explicit;
  for (const char* key : schemeOnlyKeys(other))
    if (t.has(key))
      t.fail(key, why.substr(1));
  if (expl && root.has("solver"))
    root.fail("solver", "[solver] (the linear solver of the implicit step)" + why);
}
/// [output].
void readOutput(const core::TableReader& root, Model& model) {
  if (auto o = root.optionalTable("output")) {
    model.output.field_every = intIn(*o, "field_every", 0, 10);
    model.output.energy_every = intIn(*o, "energy_every", 1, 1);
    model.output.fields = o->getBool("fields", true);
    // 0: a checkpoint only on SIGINT/SIGTERM
    model.output.checkpoint_every =
        o->getIntIn("checkpoint_every", 0, std::numeric_limits<std::int64_t>::max(), 0);
  }
}
} // namespace

/// [time], [solver] and [output].
void readTimeAndOutput(const core::TableReader& root, Model& model) {
  {
    const auto t = root.table("time");
    auto& ts = model.time;
    ts.integrator = t.getChoice("integrator", kIntegratorKindNames,
                                model.kind == ModelKind::LargeDeflection ? IntegratorKind::Explicit
                                                                         : IntegratorKind::Newmark);
    if (ts.integrator == IntegratorKind::Newmark && model.kind == ModelKind::LargeDeflection)
      t.fail("integrator", "the large-deflection model needs integrator = \"explicit\"");
    // Row sums of M_D vanish (B of a translation is 0): lumping would drop it.
    for (size_t k = 0; k < model.sections.size(); ++k)
      if (ts.integrator == IntegratorKind::Explicit && model.sections[k].hasMicroInertia())
        t.fail("integrator", "section[" + std::to_string(k) +
                                 "] has micro-inertia (a dispersion), which needs the Newmark "
                                 "scheme (its gradient mass cannot be lumped): use integrator = "
                                 "\"newmark\" or micro_inertia = false in the section");
    const bool expl = ts.integrator == IntegratorKind::Explicit;
    refuseOtherSchemeKeys(root, t, ts.integrator);
    ts.safety = t.getDouble("safety", ts.safety);
    if (!(ts.safety > 0 && ts.safety <= 1))
      t.fail("safety", "safety factor must be in (0, 1]");
    ts.damping = t.getDouble("damping", 0.0);
    if (!(ts.damping >= 0) || !std::isfinite(ts.damping))
      t.fail("damping", "damping must be >= 0 (1/s)");
    // Explicit: dt optional (0 = safety x stable step).
    ts.dt = expl ? t.getDouble("dt", 0.0) : t.getDouble("dt");
    if ((!expl || t.has("dt")) && (!(ts.dt > 0) || !std::isfinite(ts.dt)))
      t.fail("dt", "time step dt must be > 0");
    ts.t_end = t.getDouble("t_end");
    if (!(ts.t_end > 0))
      t.fail("t_end", "t_end must be > 0");
    // The run takes round(t_end / dt) steps: at least one, and a bounded
    // number (an explicit run without dt is checked once its step is known).
    const double steps = ts.dt > 0 ? std::round(ts.t_end / ts.dt) : 1.0;
    if (!(steps >= 1))
      t.fail("t_end", "t_end = " + core::formatShort(ts.t_end) + " s is less than half of dt = " +
                          core::formatShort(ts.dt) + " s: the run would take no step");
    if (!(steps <= kMaxSteps))
      t.fail("dt", "t_end / dt = " + core::formatShort(steps) + " steps; at most " +
                       core::formatShort(kMaxSteps) + " (raise dt or lower t_end)");
    ts.beta1 = t.getDouble("beta1", 0.5);
    ts.beta2 = t.getDouble("beta2", 0.5);
    if (ts.beta1 < 0 || ts.beta1 > 1)
      t.fail("beta1", "must be in [0, 1]");
    if (ts.beta2 < 0 || ts.beta2 > 1)
      t.fail("beta2", "must be in [0, 1]");
    ts.hht_alpha = t.getDouble("hht_alpha", 0.0);
    if (ts.hht_alpha < -1.0 / 3 || ts.hht_alpha > 0)
      t.fail("hht_alpha", "HHT alpha must be in [-1/3, 0]");
    if (ts.hht_alpha != 0 && (t.has("beta1") || t.has("beta2")))
      t.fail("hht_alpha", "with hht_alpha, beta1 and beta2 follow from alpha: do not give them");
    if (ts.hht_alpha != 0) {
      ts.beta1 = 0.5 - ts.hht_alpha;
      ts.beta2 = 0.5 * (1 - ts.hht_alpha) * (1 - ts.hht_alpha);
    }
    // The explicit scheme lumps the mass (row sums): its energies use that mass too.
    ts.lumped = expl || t.getChoice("mass", {{"consistent", false}, {"lumped", true}}, false);
  }
  if (auto s = root.optionalTable("solver")) {
    auto& ts = model.time;
    ts.solver = s->getChoice("type", kLinearSolverKindNames, LinearSolverKind::Cg);
    ts.tolerance = s->getDouble("tolerance", ts.tolerance);
    if (!(ts.tolerance > 0 && ts.tolerance < 1))
      s->fail("tolerance", "must be in (0, 1)");
    ts.max_iterations = intIn(*s, "max_iterations", 1, ts.max_iterations);
    ts.projection = static_cast<int>(s->getIntIn("projection", 0, 100, ts.projection));
    ts.drag_iterations = intIn(*s, "drag_iterations", 1, ts.drag_iterations);
    ts.drag_tolerance = s->getDouble("drag_tolerance", ts.drag_tolerance);
  }
  readOutput(root, model);
}

/// Features only the explicit integrator has.
void checkIntegrator(const core::TableReader& root, const Model& model) {
  if (model.time.integrator != IntegratorKind::Explicit && !model.contact.empty())
    root.fail("rigid_surface", "rigid_surface needs time.integrator = \"explicit\"");
}

/// [[probe]].
void readProbes(const core::TableReader& root, Model& model) {
  const Mesh& mesh = model.mesh;
  std::set<std::string> names;
  for (const auto& r : root.tableArray("probe")) {
    Probe p;
    p.name = r.getString("name");
    if (const std::string why = core::nameProblem(p.name); !why.empty())
      r.fail("name", "probe name " + why); // names a CSV column
    if (!names.insert(p.name).second)
      r.fail("name", "duplicate probe '" + p.name + "'");
    p.node = nodeAt(mesh, readPoint(r, "at"), r, "at");
    model.probes.push_back(p);
  }
}

} // namespace lamina::membrane::case_io
