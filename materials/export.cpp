#include "materials/export.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "materials/conversions.hpp"
#include "materials/symmetry.hpp"

#include <cstdio>
#include <cstring>
#include <sstream>
#include <vector>

namespace lamina::materials {

namespace {
std::string cardName(const std::string& name) {
  std::string out;
  for (char ch : name)
    out += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::toupper(ch)) : '_';
  return out;
}

// Abaqus reads lines of up to 256 characters, CalculiX of up to 132: both
// take 8 values per data line. Abaqus gets 17 significant digits (8 x 24
// characters fit); CalculiX gets 9 ("%.9g" is at most 15 characters, so a
// line of 8 comma-separated values stays within 127).
std::string abaqusLike(const Material& m, const std::string& type, bool full) {
  std::ostringstream os;
  const auto v = abaqusCardValues(m.C.matrix());
  auto f = [full](double x) { return full ? core::formatExact(x) : core::formatShort(x, 9); };
  os << "** lamina material '" << m.name << "' (" << m.kind << "), SI units: Pa, kg/m^3\n"
     << "** D1111 D1122 D2222 D1133 D2233 D3333 D1112 D2212\n"
     << "** D3312 D1212 D1113 D2213 D3313 D1213 D1313 D1123\n"
     << "** D2223 D3323 D1223 D1323 D2323\n"
     << "*MATERIAL, NAME=" << cardName(m.name) << "\n"
     << "*ELASTIC, TYPE=" << type << "\n";
  for (std::size_t i = 0; i < v.size(); ++i)
    os << f(v[i]) << ((i % 8 == 7 || i + 1 == v.size()) ? "\n" : (full ? ", " : ","));
  os << "*DENSITY\n" << f(m.density) << "\n";
  return os.str();
}

// One LS-DYNA fixed-format field of @p width columns: right-justified, at
// most width - 1 characters so neighbouring fields stay apart, with as many
// significant digits as fit (3-4 in 10 columns, 13-17 in 20 for a stiffness in Pa).
std::string field(double x, int width) {
  char buf[48];
  if (x == 0) {
    std::snprintf(buf, sizeof buf, "%*s", width, "0.0");
    return buf;
  }
  for (int p = 16; p >= 0; --p) {
    std::snprintf(buf, sizeof buf, "%.*g", p + 1, x);
    if (static_cast<int>(std::strlen(buf)) < width)
      break;
    std::snprintf(buf, sizeof buf, "%.*E", p, x);
    if (static_cast<int>(std::strlen(buf)) < width)
      break;
  }
  char out[64];
  std::snprintf(out, sizeof out, "%*s", width, buf);
  return out;
}

// *MAT_ANISOTROPIC_ELASTIC (MAT_002) in fixed format, 8 fields per card.
// Large format (@p large): the keyword carries the "+" suffix (LS-DYNA R7.1
// and later) and every field is 20 columns wide, 160 per card, keeping 13
// significant digits. Standard format: 10-column fields, 80 per card, 3-4 digits.
std::string lsdyna(const Material& m, bool large) {
  const auto c = lsdynaCardValues(m.C.matrix());
  const int w = large ? 20 : 10;
  std::ostringstream os;
  auto card = [&](const std::vector<double>& values) {
    for (double x : values)
      os << field(x, w);
    os << "\n";
  };
  auto header = [&](const std::vector<std::string>& names) {
    os << "$";
    for (std::size_t i = 0; i < names.size(); ++i)
      os << std::string(static_cast<std::size_t>(w) - names[i].size() - (i == 0 ? 1 : 0), ' ')
         << names[i];
    os << "\n";
  };
  os << "$ lamina material '" << m.name << "' (" << m.kind << "), SI units: Pa, kg/m^3, m, s\n"
     << "$ C in xx yy zz xy yz zx order (engineering shear), upper triangle by columns\n"
     << (large ? "$ large format: 20-column fields\n"
               : "$ standard format: 10-column fields keep 3-4 digits; lsdyna gives 13+\n")
     << "*MAT_ANISOTROPIC_ELASTIC_TITLE" << (large ? "+" : "") << "\n"
     << m.name.substr(0, large ? 160 : 80) << "\n";
  header({"MID", "RO", "C11", "C12", "C22", "C13", "C23", "C33"});
  os << std::string(static_cast<std::size_t>(w) - 1, ' ') << "1";
  card({m.density, c[0], c[1], c[2], c[3], c[4], c[5]});
  header({"C14", "C24", "C34", "C44", "C15", "C25", "C35", "C45"});
  card({c[6], c[7], c[8], c[9], c[10], c[11], c[12], c[13]});
  // AOPT = 2: globally orthotropic axes from vectors A = x and D = y, so the
  // constants act in the global frame exactly as lamina stores them.
  header({"C55", "C16", "C26", "C36", "C46", "C56", "C66", "AOPT"});
  card({c[14], c[15], c[16], c[17], c[18], c[19], c[20], 2.0});
  header({"XP", "YP", "ZP", "A1", "A2", "A3", "MACF"});
  card({0, 0, 0, 1, 0, 0, 1});
  header({"V1", "V2", "V3", "D1", "D2", "D3", "BETA", "REF"});
  card({0, 0, 0, 0, 1, 0, 0, 0});
  return os.str();
}
} // namespace

nlohmann::json matrixToJson(const Matrix6& c) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 6; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int k = 0; k < 6; ++k)
      row.push_back(c(i, k));
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json materialToJson(const Material& m) {
  nlohmann::json j;
  j["name"] = m.name;
  j["C"] = matrixToJson(m.C.matrix());
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
      plies.push_back(
          {{"material", p.material}, {"angle_deg", p.angle_deg}, {"thickness", p.thickness}});
    j["plies"] = plies;
  }
  if (!m.side_file.empty())
    j["side_file"] = m.side_file;
  if (!m.side_checksum.empty())
    j["side_checksum"] = m.side_checksum;
  if (!m.phases.empty()) {
    nlohmann::json phases = nlohmann::json::array();
    for (const ReducedOrderPhase& p : m.phases) {
      nlohmann::json ph = {{"name", p.name},
                           {"density", p.density},
                           {"law", toString(p.law.kind)},
                           {"C", matrixToJson(p.law.C.matrix())}};
      if (p.law.gvbo) {
        nlohmann::json g = {{"E0", p.law.gvbo->E0}, {"nu0", p.law.gvbo->nu0}};
        for (const auto& [key, member] : gvboTableKeys())
          g[key] = (*p.law.gvbo).*member;
        ph["gvbo"] = g;
      }
      phases.push_back(ph);
    }
    j["phases"] = phases;
  }
  if (m.dispersion) {
    j["dispersion"] = matrixToJson(*m.dispersion);
    const auto l = dispersionLengths(m);
    j["dispersion_lengths"] = l;
  }
  if (m.cell_size)
    j["cell_size"] = {(*m.cell_size)[0], (*m.cell_size)[1], (*m.cell_size)[2]};
  if (!m.provenance.empty()) {
    std::ostringstream os;
    os << toml::json_formatter{m.provenance};
    j["provenance"] = nlohmann::json::parse(os.str());
  }
  return j;
}

ExportFormat parseExportFormat(const std::string& name) {
  return kExportFormatNames.parseOrThrow(name, "export format", {"--format", 0, name});
}

std::string exportCard(const Material& m, ExportFormat format) {
  // Names are written into comment and keyword lines of the cards: a
  // newline or control character there would start a line of its own.
  core::checkName(m.name, "material name");
  for (const Ply& p : m.plies)
    core::checkName(p.material, "ply material name");
  if (m.kind == kReducedOrderKind && format != ExportFormat::Json)
    throw Error("'" + m.name +
                    "' is a reduced-order cell, a nonlinear law that no elastic card "
                    "represents (its C is only the instantaneous stiffness at J = 1); "
                    "`--format json` exports its data",
                {"--format", 0, ""});
  switch (format) {
  case ExportFormat::Abaqus:
    return abaqusLike(m, "ANISOTROPIC", true);
  case ExportFormat::Calculix:
    return abaqusLike(m, "ANISO", false);
  case ExportFormat::Lsdyna:
    return lsdyna(m, true);
  case ExportFormat::LsdynaSmall:
    return lsdyna(m, false);
  case ExportFormat::Json:
    break;
  }
  return materialToJson(m).dump(2) + "\n";
}

} // namespace lamina::materials
