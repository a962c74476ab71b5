#include "materials/entries.hpp"

#include "materials/export.hpp"
#include "materials/layup.hpp"
#include "materials/reduced_order_law.hpp"

#include <ctime>

#ifndef LAMINA_VERSION
#define LAMINA_VERSION "unknown"
#endif

namespace lamina::materials {

namespace {

/// @return the UTC time now as "YYYY-MM-DDTHH:MM:SSZ"
std::string nowIso() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

} // namespace

void stampProvenance(Material& m, const std::string& program) {
  m.provenance.insert("program", program);
  m.provenance.insert("version", LAMINA_VERSION);
  m.provenance.insert("time", nowIso());
}

Material catalogEntry(const Catalog& catalog, const std::string& key, const std::string& name,
                      const std::string& program) {
  Material m = catalog.get(key).toMaterial();
  m.provenance.insert("catalog_key", key);
  m.name = name;
  stampProvenance(m, program);
  return m;
}

Material layupEntry(const std::string& name, const std::vector<Ply>& plies, MaterialSource& source,
                    const std::string& program) {
  Material m = makeLayup(name, plies, [&](const std::string& n) { return source.get(n); });
  stampProvenance(m, program);
  return m;
}

nlohmann::json showJson(const Library& library, const Material& m) {
  nlohmann::json j = materialToJson(m);
  if (m.kind != kReducedOrderKind)
    return j;
  const ReducedOrderLaw law(m.name, readReducedOrderEntry(library, m));
  const std::vector<int> count = law.model().partitionsPerPhase();
  for (std::size_t p = 0; p < m.phases.size(); ++p)
    j["phases"][p]["partitions"] = count[p];
  j["state_doubles"] = law.stateSize();
  j["nonlinear_partitions"] = law.nonlinearPartitions().size();
  j["scheme"] = toString(law.model().scheme);
  return j;
}

} // namespace lamina::materials
