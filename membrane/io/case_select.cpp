/// @file case_select.cpp
/// @brief Points, directions and node/element selections of case tables.

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>
#include <set>

namespace lamina::membrane::case_io {

Eigen::Vector2d readPoint(const core::TableReader& r, const std::string& key) {
  const auto v = r.getDoubleArray(key);
  if (v.size() != 2)
    r.fail(key, "expected [x, y]");
  return {v[0], v[1]};
}

Eigen::Vector3d readDirection(const core::TableReader& r, const Eigen::Vector3d& fallback) {
  if (r.has("direction") && r.has("inclination_deg"))
    r.fail("direction", "give either direction or inclination_deg, not both");
  if (r.has("direction")) {
    const auto v = r.getDoubleArray("direction");
    if (v.size() != 3)
      r.fail("direction", "expected [dx, dy, dz]");
    Eigen::Vector3d d(v[0], v[1], v[2]);
    if (!(d.norm() > 0))
      r.fail("direction", "direction must be non-zero");
    return d.normalized();
  }
  if (r.has("inclination_deg")) {
    // Tilted from the normal +z towards +x (Table 2 cases 2 and 4: 30 degrees).
    const double a = r.getDouble("inclination_deg") * kPi / 180;
    return {std::sin(a), 0.0, std::cos(a)};
  }
  return fallback;
}

namespace {
/// The keys that select nodes or elements; a table gives at most one.
constexpr const char* kSelectorKeys[] = {"nodes", "box", "at", "region", "all"};

int selectorKeyCount(const core::TableReader& r) {
  int count = 0;
  for (const char* k : kSelectorKeys)
    if (r.has(k))
      ++count;
  return count;
}
} // namespace

Selector readSelector(const core::TableReader& r) {
  Selector s;
  const int count = selectorKeyCount(r);
  if (count != 1)
    r.failHere("give exactly one of nodes, box, at, region, all");
  if (r.has("nodes")) {
    s.kind = SelectBy::Nodes;
    s.key = "nodes";
    s.name = r.getString("nodes");
  } else if (r.has("box")) {
    s.kind = SelectBy::Box;
    s.key = "box";
    const auto v = r.getDoubleArray("box");
    if (v.size() != 4 || !(v[0] <= v[1]) || !(v[2] <= v[3]))
      r.fail("box", "expected [xmin, xmax, ymin, ymax]");
    std::copy(v.begin(), v.end(), s.box.begin());
  } else if (r.has("at")) {
    s.kind = SelectBy::At;
    s.key = "at";
    s.at = readPoint(r, "at");
  } else if (r.has("region")) {
    s.kind = SelectBy::Region;
    s.key = "region";
    s.name = r.getString("region");
  } else {
    s.kind = SelectBy::All;
    s.key = "all";
    if (!r.getBool("all", false))
      r.fail("all", "all = false selects nothing");
  }
  return s;
}

Selector readSelectorOrAll(const core::TableReader& r) {
  return selectorKeyCount(r) == 0 ? Selector{SelectBy::All, "", {}, {}, "all"} : readSelector(r);
}

int regionIndex(const Mesh& m, const std::string& name, const core::TableReader& r,
                const std::string& key) {
  for (size_t i = 0; i < m.regions.size(); ++i)
    if (m.regions[i] == name)
      return static_cast<int>(i);
  std::string have;
  for (const auto& n : m.regions)
    have += (have.empty() ? "" : ", ") + n;
  r.fail(key, "mesh " + m.source + " has no region '" + name + "' (regions: " + have + ")");
}

/// The node nearest to @p p, which must lie on mesh @p m: within its longest
/// edge of a node (a point off the mesh is a typo, not a request for the
/// nearest boundary node).
int nodeAt(const Mesh& m, const Eigen::Vector2d& p, const core::TableReader& r,
           const std::string& key) {
  const int i = m.nearestNode(p);
  if (i < 0 || !((m.nodes[i] - p).norm() <= m.maxEdge())) {
    const auto [x0, x1, y0, y1] = m.bounds();
    r.fail(key, "point (" + core::formatShort(p.x()) + ", " + core::formatShort(p.y()) +
                    ") lies outside mesh " + m.source + " (x in [" + core::formatShort(x0) + ", " +
                    core::formatShort(x1) + "], y in [" + core::formatShort(y0) + ", " +
                    core::formatShort(y1) + "])");
  }
  return i;
}

namespace {
bool inBox(const Eigen::Vector2d& p, const std::array<double, 4>& b, double tol) {
  return p.x() >= b[0] - tol && p.x() <= b[1] + tol && p.y() >= b[2] - tol && p.y() <= b[3] + tol;
}

/// The triangle of @p m containing @p p (barycentric test, with a relative
/// tolerance of 1e-12 of its area) with the lowest user number (on a shared
/// edge or corner, whatever the run's order), -1 if none.
int elementAt(const Mesh& m, const Eigen::Vector2d& p) {
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  int found = -1;
  for (int e = 0; e < m.numElements(); ++e) {
    const auto& t = m.triangles[e];
    const Eigen::Vector2d a = m.nodes[t[0]], b = m.nodes[t[1]], c = m.nodes[t[2]];
    const double A2 = cross(b - a, c - a), eps = -1e-12 * A2;
    if (cross(b - a, p - a) >= eps && cross(c - b, p - b) >= eps && cross(a - c, p - c) >= eps &&
        (found < 0 || m.elementLabel(e) < m.elementLabel(found)))
      found = e;
  }
  return found;
}

/// What a selection yields: node or element indices.
enum class Items { Nodes, Elements };

/// The @p items of @p m that @p s selects (not empty; errors name @p r's
/// keys): a box holds a node or an element's centroid, `at` is the node
/// there or the triangle containing the point, a region is its elements or
/// their nodes, a node set selects nodes only.
std::vector<int> selectItems(const Mesh& m, const Selector& s, const core::TableReader& r,
                             Items items) {
  const bool nodes = items == Items::Nodes;
  const int n = nodes ? m.numNodes() : m.numElements();
  std::vector<int> out;
  switch (s.kind) {
  case SelectBy::Nodes: {
    if (!nodes)
      r.fail("nodes", "this load acts on elements: select them with box, at, region or all");
    auto it = m.node_sets.find(s.name);
    if (it == m.node_sets.end()) {
      std::string have;
      for (const auto& [name, v] : m.node_sets)
        have += (have.empty() ? "" : ", ") + name;
      r.fail("nodes",
             "mesh " + m.source + " has no node set '" + s.name + "' (sets: " + have + ")");
    }
    out = it->second;
    break;
  }
  case SelectBy::Box: {
    const double tol = 1e-9 * m.maxEdge();
    for (int i = 0; i < n; ++i)
      if (inBox(nodes ? m.nodes[i] : m.centroid(i), s.box, tol))
        out.push_back(i);
    break;
  }
  case SelectBy::At: {
    const int i = nodes ? nodeAt(m, s.at, r, "at") : elementAt(m, s.at);
    if (i >= 0)
      out.push_back(i);
    break;
  }
  case SelectBy::Region: {
    const int reg = regionIndex(m, s.name, r, "region");
    std::set<int> corners; // the region's nodes, each once, in order
    for (int e = 0; e < m.numElements(); ++e)
      if (m.region_of[e] == reg) {
        if (nodes)
          corners.insert(m.triangles[e].begin(), m.triangles[e].end());
        else
          out.push_back(e);
      }
    if (nodes)
      out.assign(corners.begin(), corners.end());
    break;
  }
  case SelectBy::All:
    out.resize(static_cast<std::size_t>(n));
    std::iota(out.begin(), out.end(), 0);
    break;
  }
  if (out.empty())
    r.fail(s.key,
           std::string("selects no ") + (nodes ? "node" : "element") + " of mesh " + m.source);
  return out;
}
} // namespace

std::vector<int> selectNodes(const Mesh& m, const Selector& s, const core::TableReader& r) {
  return selectItems(m, s, r, Items::Nodes);
}

std::vector<int> selectElements(const Mesh& m, const Selector& s, const core::TableReader& r) {
  return selectItems(m, s, r, Items::Elements);
}

/// Parses `components` (a subset of "xyz") into component indices.
std::vector<int> readComponents(const core::TableReader& r) {
  const std::string comps = r.getString("components", "xyz");
  std::vector<int> out;
  for (char ch : comps) {
    const auto k = std::string("xyz").find(ch);
    if (k == std::string::npos || std::count(comps.begin(), comps.end(), ch) > 1)
      r.fail("components", "components is a subset of \"xyz\"");
    out.push_back(static_cast<int>(k));
  }
  if (out.empty())
    r.fail("components", "components is a subset of \"xyz\"");
  return out;
}

} // namespace lamina::membrane::case_io
