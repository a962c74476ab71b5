#include "materials/export.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "materials/conversions.hpp"
#include "materials/symmetry.hpp"

#include <sstream>

namespace lamina::materials {

namespace {
std::string cardName(const std::string& name) {
  std::string out;
  for (char ch : name)
    out += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::toupper(ch)) : '_';
  return out;
}

std::string abaqusLike(const Material& m, const std::string& type) {
  std::ostringstream os;
  const auto v = abaqusCardValues(m.C.matrix());
  os << "** lamina material '" << m.name << "' (" << m.kind << "), SI units: Pa, kg/m^3\n"
     << "** D1111 D1122 D2222 D1133 D2233 D3333 D1112 D2212 D3312 D1212 D1113 D2213 D3313 "
        "D1213 D1313 D1123 D2223 D3323 D1223 D1323 D2323\n"
     << "*MATERIAL, NAME=" << cardName(m.name) << "\n"
     << "*ELASTIC, TYPE=" << type << "\n";
  for (std::size_t i = 0; i < v.size(); ++i)
    os << core::formatExact(v[i]) << ((i % 8 == 7 || i + 1 == v.size()) ? "\n" : ", ");
  os << "*DENSITY\n" << core::formatExact(m.density) << "\n";
  return os.str();
}

std::string lsdyna(const Material& m) {
  const auto c = lsdynaCardValues(m.C.matrix());
  std::ostringstream os;
  auto f = [](double x) { return core::formatExact(x); };
  os << "$ lamina material '" << m.name << "' (" << m.kind << "), SI units: Pa, kg/m^3, m, s\n"
     << "$ C in xx yy zz xy yz zx order (engineering shear), upper triangle by columns\n"
     << "*MAT_ANISOTROPIC_ELASTIC_TITLE\n"
     << m.name << "\n"
     << "$     MID,       RO,      C11,      C12,      C22,      C13,      C23,      C33\n"
     << "1," << f(m.density);
  for (std::size_t i = 0; i < 6; ++i)
    os << "," << f(c[i]);
  os << "\n$     C14,      C24,      C34,      C44,      C15,      C25,      C35,      C45\n";
  for (std::size_t i = 6; i < 14; ++i)
    os << (i > 6 ? "," : "") << f(c[i]);
  os << "\n$     C55,      C16,      C26,      C36,      C46,      C56,      C66,     AOPT\n";
  for (std::size_t i = 14; i < 21; ++i)
    os << (i > 14 ? "," : "") << f(c[i]);
  // AOPT = 2: globally orthotropic axes from vectors A = x and D = y, so the
  // constants act in the global frame exactly as lamina stores them.
  os << ",2.0\n"
     << "$      XP,       YP,       ZP,       A1,       A2,       A3,     MACF\n"
     << "0.0,0.0,0.0,1.0,0.0,0.0,1\n"
     << "$      V1,       V2,       V3,       D1,       D2,       D3,     BETA,      REF\n"
     << "0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0\n";
  return os.str();
}
} // namespace

nlohmann::json materialToJson(const Material& m) {
  nlohmann::json j;
  j["name"] = m.name;
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 6; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int k = 0; k < 6; ++k)
      row.push_back(m.C(i, k));
    rows.push_back(row);
  }
  j["C"] = rows;
  j["density"] = m.density;
  j["kind"] = m.kind;
  const Symmetry s = classify(m.C);
  j["symmetry"] = toString(s.cls);
  if (s.axis >= 0)
    j["symmetry_axis"] = std::string(1, "xyz"[s.axis]);
  j["anisotropy_index"] = anisotropyIndex(m.C);
  const EngineeringConstants e = m.C.engineering();
  j["engineering"] = {{"E1", e.E1},     {"E2", e.E2},     {"E3", e.E3},     {"G12", e.G12},
                      {"G23", e.G23},   {"G13", e.G13},   {"nu12", e.nu12}, {"nu13", e.nu13},
                      {"nu23", e.nu23}, {"nu21", e.nu21}, {"nu31", e.nu31}, {"nu32", e.nu32}};
  if (m.thickness)
    j["thickness"] = *m.thickness;
  if (!m.plies.empty()) {
    nlohmann::json plies = nlohmann::json::array();
    for (const Ply& p : m.plies)
      plies.push_back({{"material", p.material}, {"angle_deg", p.angle_deg}, {"thickness", p.thickness}});
    j["plies"] = plies;
  }
  if (!m.side_file.empty())
    j["side_file"] = m.side_file;
  if (!m.provenance.empty()) {
    std::ostringstream os;
    os << toml::json_formatter{m.provenance};
    j["provenance"] = nlohmann::json::parse(os.str());
  }
  return j;
}

std::string exportCard(const Material& m, const std::string& format) {
  if (format == "abaqus")
    return abaqusLike(m, "ANISOTROPIC");
  if (format == "calculix")
    return abaqusLike(m, "ANISO");
  if (format == "lsdyna")
    return lsdyna(m);
  if (format == "json")
    return materialToJson(m).dump(2) + "\n";
  throw Error("unknown export format '" + format + "' (abaqus, lsdyna, calculix, json)",
              {"--format", 0, format});
}

} // namespace lamina::materials
