#include "materials/library.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "materials/law_spec.hpp"

#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

namespace lamina::materials {

namespace {

constexpr const char* kFormat = "lamina-materials-library";
constexpr std::int64_t kVersion = 1;

bool isBareKey(const std::string& k) {
  if (k.empty())
    return false;
  for (char ch : k)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
      return false;
  return true;
}

std::string quoteBasic(const std::string& s) {
  std::string out = "\"";
  for (unsigned char ch : s) {
    switch (ch) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\t':
      out += "\\t";
      break;
    case '\r':
      out += "\\r";
      break;
    default:
      if (ch < 0x20 || ch == 0x7f) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", ch);
        out += buf;
      } else {
        out += static_cast<char>(ch);
      }
    }
  }
  return out + "\"";
}

std::string key(const std::string& k) {
  return isBareKey(k) ? k : quoteBasic(k);
}

std::string stringValue(const std::string& s) {
  // Multi-line text (e.g. the input file that made an entry) as a literal
  // block, which keeps the library diffable; otherwise a basic string.
  bool literalOk = s.find('\n') != std::string::npos && s.find("'''") == std::string::npos;
  for (unsigned char ch : s)
    if ((ch < 0x20 && ch != '\n' && ch != '\t') || ch == 0x7f)
      literalOk = false;
  if (literalOk && s.back() != '\'')
    return "'''\n" + s + "'''";
  return quoteBasic(s);
}

std::string value(const toml::node& n);

std::string inlineTable(const toml::table& t) {
  std::string out = "{ ";
  bool first = true;
  for (const auto& [k, v] : t) {
    out += (first ? "" : ", ") + key(std::string(k.str())) + " = " + value(v);
    first = false;
  }
  return out + (first ? "}" : " }");
}

std::string value(const toml::node& n) {
  if (auto s = n.value_exact<std::string>())
    return stringValue(*s);
  if (auto i = n.value_exact<std::int64_t>())
    return std::to_string(*i);
  if (auto d = n.value_exact<double>())
    return core::formatExact(*d);
  if (auto b = n.value_exact<bool>())
    return *b ? "true" : "false";
  if (const toml::array* a = n.as_array()) {
    std::string out = "[";
    bool first = true;
    for (const toml::node& e : *a) {
      out += (first ? "" : ", ") + value(e);
      first = false;
    }
    return out + "]";
  }
  if (const toml::table* t = n.as_table())
    return inlineTable(*t);
  std::ostringstream os; // dates and times: keep their TOML text as a string
  n.visit([&os](const auto& v) { os << v; });
  return quoteBasic(os.str());
}

/// Permission bits of side files and of the side folder.
struct FileModes {
  mode_t file = 0644;   ///< a side file's: those of the library
  mode_t folder = 0755; ///< the side folder's at most: rwx for the owner (who
                        ///< writes in it), the library's bits for the others, x where r
};

/// @return the modes of the side files of the library at @p library (a new
/// library is written 0644, see core::writeFileAtomically)
FileModes sideModes(const std::filesystem::path& library) {
  struct stat st {};
  FileModes m;
  if (::stat(library.c_str(), &st) == 0)
    m.file = st.st_mode & 0666;
  // the owner always keeps rwx (a 0444 library must still take new entries);
  // group and others get the library's bits, x where r
  m.folder = 0700 | (m.file & 0066) | ((m.file & 0044) >> 2);
  return m;
}

/// The side files of one transaction: written into a fresh stage folder
/// inside the side folder, under names unique to the transaction (the
/// stage's random suffix), then renamed into the side folder. Nothing is
/// overwritten, so the library write is the one commit point: until it, the
/// library names the previous files, which stay; after it, the previous
/// files are named by nothing and swept.
class SideFiles {
public:
  /// Names of stage folders start with this ("<stem>.side/.stage.XXXXXX").
  static constexpr const char* kStagePrefix = ".stage.";

  SideFiles(std::filesystem::path folder, FileModes modes)
      : folder_(std::move(folder)), modes_(modes) {}
  ~SideFiles() {
    std::error_code ec;
    if (!stage_.empty())
      std::filesystem::remove_all(stage_, ec);
  }
  SideFiles(const SideFiles&) = delete;
  SideFiles& operator=(const SideFiles&) = delete;

  /// Creates the stage folder and @return the unique stem "<name>.XXXXXX"
  /// its files are to be named with.
  std::string open(const std::string& name) {
    std::filesystem::create_directories(folder_);
    struct stat st {};
    if (::stat(folder_.c_str(), &st) == 0 &&
        (st.st_mode & 07777) != ((st.st_mode & 07777 & modes_.folder) | 0700))
      ::chmod(folder_.c_str(), (st.st_mode & 07777 & modes_.folder) | 0700); // no more open than the library
    std::string tmpl = (folder_ / (std::string(kStagePrefix) + "XXXXXX")).string();
    if (!::mkdtemp(tmpl.data()))
      throw Error("cannot create a temporary folder for side files", {folder_.string(), 0, ""});
    stage_ = tmpl;
    return name + "." + tmpl.substr(tmpl.size() - 6);
  }
  /// @return the stage folder
  const std::filesystem::path& stage() const { return stage_; }

  /// Renames every file of the stage into the side folder.
  void place() {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(stage_))
      if (e.is_regular_file())
        files.push_back(e.path());
    for (const auto& f : files) {
      if (::chmod(f.c_str(), modes_.file) != 0)
        throw Error("cannot set the permissions of a side file", {f.string(), 0, ""});
      const std::filesystem::path to = folder_ / f.filename();
      core::renameIntoPlace(f, to);
      placed_.push_back(to);
    }
  }

  /// Undoes place(): removes what it placed.
  void rollBack() {
    std::error_code ec;
    for (const auto& p : placed_)
      std::filesystem::remove(p, ec);
    placed_.clear();
  }

private:
  std::filesystem::path folder_, stage_;
  FileModes modes_;
  std::vector<std::filesystem::path> placed_;
};

/// @return whether @p s is a fileChecksum(): "fnv1a64:" and 16 lower-case hex digits
bool isChecksum(const std::string& s) {
  const std::string prefix = "fnv1a64:";
  if (s.size() != prefix.size() + 16 || s.compare(0, prefix.size(), prefix) != 0)
    return false;
  for (std::size_t i = prefix.size(); i < s.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(s[i])) ||
        std::isupper(static_cast<unsigned char>(s[i])))
      return false;
  return true;
}

Material readEntry(const core::TableReader& t, const std::string& name) {
  if (const std::string why = core::nameProblem(name); !why.empty())
    t.failHere("material name " + why + " (names: docs/reliability.md)");
  Material m;
  m.name = name;
  m.kind = t.getString("kind");
  if (m.kind != "catalog" && m.kind != "homogenized" && m.kind != "layup" &&
      m.kind != "constants" && m.kind != kReducedOrderKind)
    t.fail("kind",
           "unknown kind '" + m.kind + "' (catalog, homogenized, layup, constants, reduced-order)");
  m.density = t.getDouble("density");
  m.C = Stiffness(readMatrix6(t, "C", "Pa"));
  if (t.has("dispersion"))
    m.dispersion = readMatrix6(t, "dispersion", "zeta^2 D, kg/m");
  if (t.has("cell_size")) {
    const auto v = t.getDoubleArray("cell_size");
    if (v.size() != 3)
      t.fail("cell_size", "expected 3 edge lengths (m)");
    m.cell_size = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  if (t.has("thickness"))
    m.thickness = t.getDouble("thickness");
  m.side_file = t.getString("side_file", "");
  for (const auto& part : std::filesystem::path(m.side_file))
    if (m.side_file.front() == '/' || part == "..")
      t.fail("side_file", "must be a path inside the library's folder (relative, without '..')");
  m.side_checksum = t.getString("side_checksum", "");
  if (!m.side_checksum.empty() && !isChecksum(m.side_checksum))
    t.fail("side_checksum", "expected \"fnv1a64:\" and 16 hexadecimal digits");
  for (const core::TableReader& p : t.tableArray("phases")) {
    ReducedOrderPhase ph;
    ph.name = p.getString("name");
    ph.density = p.getDouble("density");
    ph.law = readLawSpec(p);
    m.phases.push_back(std::move(ph));
  }
  if (m.kind == kReducedOrderKind && m.side_file.empty())
    t.fail("side_file", "a reduced-order entry needs its side file (the cell's arrays, written "
                        "by `homogenize --reduced-order`)");
  if (m.kind == kReducedOrderKind && m.side_checksum.empty())
    t.fail("side_checksum", "a reduced-order entry needs the checksum of its side file");
  for (const core::TableReader& p : t.tableArray("plies")) {
    m.plies.push_back(
        {p.getString("material"), p.getDouble("angle_deg"), p.getDouble("thickness")});
    if (const std::string why = core::nameProblem(m.plies.back().material); !why.empty())
      p.fail("material", "material name " + why);
    if (!(m.plies.back().thickness > 0))
      p.fail("thickness", "ply thickness must be positive (m)");
  }
  if (const toml::node* prov = t.raw("provenance")) {
    if (!prov->is_table())
      t.fail("provenance", "expected a table");
    m.provenance = *prov->as_table();
  }
  // Name the key at fault: density and thickness here, the stiffness below.
  if (!(m.density > 0) || !std::isfinite(m.density))
    t.fail("density", "density must be positive and finite (kg/m^3)");
  if (m.thickness && (!(*m.thickness > 0) || !std::isfinite(*m.thickness)))
    t.fail("thickness", "thickness must be positive and finite (m)");
  try {
    validate(m);
  } catch (const Error& e) {
    const std::string msg = e.message();
    const char* keys[] = {"dispersion", "cell_size", "side_checksum", "phases"};
    const char* at = "C";
    for (const char* k : keys)
      if (msg.rfind(k, 0) == 0)
        at = k;
    t.fail(at, msg);
  }
  return m;
}

} // namespace

std::filesystem::path Library::resolvePath(const std::string& cli_path) {
  if (!cli_path.empty())
    return cli_path;
  if (const char* env = std::getenv(kEnvVar); env && *env)
    return env;
  if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "lamina" / "library.toml";
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home && *home ? home : ".") / ".local" / "share" / "lamina" /
         "library.toml";
}

Library::Library(std::filesystem::path path) : path_(std::move(path)) {
  reload();
}

void Library::reload() {
  entries_.clear();
  if (!std::filesystem::exists(path_))
    return;
  entries_ = parse(core::readWholeFile(path_, core::kMaxTomlBytes, "materials library"),
                   path_.string());
}

std::map<std::string, Material> Library::parse(const std::string& text, const std::string& source) {
  const toml::table doc = core::parseTomlString(text, source);
  const core::TableReader root(doc, source);
  if (!root.has("lamina"))
    throw Error("not a lamina materials library (no [lamina] header table); refusing to use it",
                {source, 1, "lamina"});
  const core::TableReader head = root.table("lamina");
  if (head.getString("format") != kFormat)
    head.fail("format", std::string("not a lamina materials library (expected format = \"") +
                            kFormat + "\")");
  const std::int64_t version = head.getInt("version");
  if (version != kVersion)
    head.fail("version", "unsupported library version " + std::to_string(version));
  std::map<std::string, Material> out;
  if (auto mats = root.optionalTable("materials"))
    for (const std::string& name : mats->keys())
      out.emplace(name, readEntry(mats->table(name), name));
  root.finish();
  return out;
}

std::string Library::serialize(const std::map<std::string, Material>& entries) {
  std::ostringstream os;
  os << "# lamina materials library. Written by lamina programs; change it with `materials`.\n"
     << "# C: 6x6 stiffness in Pa, lamina order [xx, yy, zz, xy, yz, xz], engineering shear.\n"
     << "# dispersion: zeta^2 D (kg/m, same order), micro-inertia; cell_size: m.\n"
     << "[lamina]\nformat = \"" << kFormat << "\"\nversion = " << kVersion << "\n";
  for (const auto& [name, m] : entries) {
    const std::string head = "materials." + key(name);
    os << "\n[" << head << "]\n";
    os << "kind = " << quoteBasic(m.kind) << "\n";
    os << "density = " << core::formatExact(m.density) << "\n";
    if (m.thickness)
      os << "thickness = " << core::formatExact(*m.thickness) << "\n";
    if (!m.side_file.empty())
      os << "side_file = " << quoteBasic(m.side_file) << "\n";
    if (!m.side_checksum.empty())
      os << "side_checksum = " << quoteBasic(m.side_checksum) << "\n";
    writeMatrix6(os, "C", m.C.matrix());
    if (m.cell_size)
      os << "cell_size = [" << core::formatExact((*m.cell_size)[0]) << ", "
         << core::formatExact((*m.cell_size)[1]) << ", " << core::formatExact((*m.cell_size)[2])
         << "]\n";
    if (m.dispersion)
      writeMatrix6(os, "dispersion", *m.dispersion);
    if (!m.plies.empty()) {
      os << "plies = [\n";
      for (const Ply& p : m.plies)
        os << "  { material = " << quoteBasic(p.material)
           << ", angle_deg = " << core::formatExact(p.angle_deg)
           << ", thickness = " << core::formatExact(p.thickness) << " },\n";
      os << "]\n";
    }
    for (const ReducedOrderPhase& p : m.phases) {
      os << "\n[[" << head << ".phases]]\nname = " << quoteBasic(p.name)
         << "\ndensity = " << core::formatExact(p.density) << "\n";
      writeLawSpec(os, p.law);
    }
    if (!m.provenance.empty()) {
      os << "\n[" << head << ".provenance]\n";
      for (const auto& [k, v] : m.provenance)
        os << key(std::string(k.str())) << " = " << value(v) << "\n";
    }
  }
  return os.str();
}

std::vector<std::string> Library::names() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : entries_)
    out.push_back(k);
  return out;
}

const Material& Library::get(const std::string& name) const {
  auto it = entries_.find(name);
  if (it == entries_.end()) {
    const std::string list = core::joinNames(names());
    throw Error("no material '" + name + "' in library " + path_.string() +
                    " (it holds: " + (list.empty() ? std::string("nothing") : list) + ")",
                {"", 0, name});
  }
  return it->second;
}

std::filesystem::path Library::folder() const {
  return core::resolveLinks(path_).parent_path();
}

std::filesystem::path Library::sideFolder() const {
  return std::filesystem::path(core::resolveLinks(path_).stem().string() + ".side");
}

void Library::add(const Material& m, bool overwrite) {
  add(m, overwrite, SideFileWriter{});
}

void Library::add(Material m, bool overwrite, const SideFileWriter& write_side) {
  std::vector<Addition> one;
  one.push_back({std::move(m), write_side});
  add(std::move(one), overwrite);
}

void Library::checkNewNames(const std::vector<std::string>& names, bool overwrite,
                            const std::string& option) const {
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (!seen.insert(name).second)
      throw Error("two of the entries to add are named '" + name +
                      "' (nothing was added; choose values that print differently)",
                  {"", 0, option});
    if (!overwrite && contains(name))
      throw Error("entry '" + name + "' is already in library " + path_.string() +
                      " (use --overwrite or another name; nothing was added)",
                  {"", 0, option});
  }
}

void Library::add(std::vector<Addition> additions, bool overwrite) {
  std::vector<std::string> names;
  for (const Addition& a : additions) {
    validate(a.material);
    names.push_back(a.material.name);
  }
  const core::FileLock lock(path_);
  reload(); // another process may have added entries since we loaded
  checkNewNames(names, overwrite, "");
  sweep();
  const FileModes modes = sideModes(path_);
  std::vector<std::unique_ptr<SideFiles>> sides;
  try {
    auto updated = entries_;
    for (Addition& a : additions) {
      Material& m = a.material;
      if (a.write_side) {
        sides.push_back(std::make_unique<SideFiles>(folder() / sideFolder(), modes));
        const std::string stem = sides.back()->open(m.name);
        m.side_file = (sideFolder() / (stem + ".h5")).string();
        const std::filesystem::path h5 = sides.back()->stage() / (stem + ".h5");
        a.write_side(h5);
        m.side_checksum = fileChecksum(h5, "side file"); // of the bytes committed
        sides.back()->place();
      }
      updated[m.name] = m;
    }
    const std::string text = serialize(updated);
    parse(text, path_.string() + " (about to be written)"); // never write what we cannot read back
    core::writeFileAtomically(path_, text);                 // the commit point
    entries_ = std::move(updated);
  } catch (...) {
    for (auto& side : sides)
      side->rollBack();
    throw;
  }
  sweep(); // the side files of the entries just replaced
}

void Library::remove(const std::string& name) {
  const core::FileLock lock(path_);
  reload();
  get(name); // error listing what the library holds
  auto updated = entries_;
  updated.erase(name);
  core::writeFileAtomically(path_, serialize(updated));
  entries_ = std::move(updated);
  sweep(); // the entry's side files, now named by nothing
}

void Library::sweep() const {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path file = core::resolveLinks(path_);
  const std::string prefix = core::temporaryPrefix(file);
  for (const auto& e : fs::directory_iterator(file.parent_path(), ec))
    if (e.path().filename().string().rfind(prefix, 0) == 0)
      fs::remove(e.path(), ec);
  const fs::path side = folder() / sideFolder();
  if (!fs::is_directory(side, ec))
    return;
  std::set<std::string> named; // stems of the side files entries name
  for (const auto& [name, m] : entries_)
    if (!m.side_file.empty() && fs::path(m.side_file).parent_path() == sideFolder())
      named.insert(fs::path(m.side_file).stem().string());
  std::vector<fs::path> debris;
  for (const auto& e : fs::directory_iterator(side, ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind(SideFiles::kStagePrefix, 0) == 0 || !named.count(e.path().stem().string()))
      debris.push_back(e.path());
  }
  for (const auto& p : debris)
    fs::remove_all(p, ec);
}

} // namespace lamina::materials
