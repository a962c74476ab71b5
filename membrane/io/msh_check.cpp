#include "membrane/io/msh_check.hpp"

#include "core/error.hpp"
#include "core/input_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <type_traits>
#include <unordered_set>
#include <vector>

namespace lamina::membrane {
namespace {

/// Largest node, element or entity tag: gmsh 4.8 looks nodes up by an int.
constexpr long long kMaxTag = std::numeric_limits<int>::max();

/// Node count and dimension of the gmsh element types 1 to 31 (gmsh
/// reference manual, "MSH file format", element types); index 0 unused.
struct Shape {
  int nodes;
  int dim;
};
constexpr std::array<Shape, 32> kShapes = {
    {{0, -1}, {2, 1},  {3, 2},  {4, 2},  {4, 3}, {8, 3}, {6, 3},  {5, 3},  {3, 1},  {6, 2}, {9, 2},
     {10, 3}, {27, 3}, {18, 3}, {14, 3}, {1, 0}, {8, 2}, {20, 3}, {15, 3}, {13, 3}, {9, 2}, {10, 2},
     {12, 2}, {15, 2}, {15, 2}, {21, 2}, {4, 1}, {5, 1}, {6, 1},  {20, 3}, {35, 3}, {56, 3}}};

/// How a number is stored: always as text (section counts of MSH 2.2 and
/// $PhysicalNames), or, in a binary file, as a 4-byte int or an 8-byte
/// size_t; as text in an ASCII file.
enum class Field { kText, kInt, kSize };

/// The name of a value being read, for an error message. A check reads
/// millions of values and throws at most once, so the text is built only
/// when a message needs it: a Label holds a string literal, or refers to a
/// string or to a callable returning one. What it refers to must outlive
/// it; a temporary passed as an argument does (it lives to the end of the
/// call's full expression).
class Label {
public:
  /// A literal text (implicit, as are the others: call sites pass the
  /// text or the callable where a name is expected).
  Label(const char* text) : obj_(text), make_(&literal) {}
  /// The text of @p text (referred to, not copied).
  Label(const std::string& text) : obj_(&text), make_(&string) {}
  /// The text @p make returns, called only when the label is (referred to).
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, Label> &&
                                              std::is_invocable_r_v<std::string, const F&>>>
  Label(const F& make) : obj_(&make), make_(&call<F>) {}

  /// @return the text
  std::string operator()() const { return make_(obj_); }

private:
  static std::string literal(const void* p) { return static_cast<const char*>(p); }
  static std::string string(const void* p) { return *static_cast<const std::string*>(p); }
  template <class F>
  static std::string call(const void* p) {
    return (*static_cast<const F*>(p))();
  }

  const void* obj_;
  std::string (*make_)(const void*);
};

/// @return a callable giving @p base's text followed by @p suffix (built
/// when called; @p base is copied, so it may be a Label or a lambda)
template <class Base>
auto join(Base base, const char* suffix) {
  return [base, suffix] { return base() + suffix; };
}

/// Reads the file's bytes front to back and reports where it stopped.
class Cursor {
public:
  Cursor(const std::string& text, const std::string& file) : t_(text), file_(file) {}

  std::string section = "$MeshFormat"; ///< the section being read, for messages
  bool binary = false;                 ///< the file is binary (MeshFormat's file-type 1)

  /// Throws the error at the current position: the line in an ASCII part,
  /// the byte offset in a binary one.
  [[noreturn]] void fail(const std::string& what) const {
    if (binary && inData_)
      throw Error(section + ": " + what + " (byte " + std::to_string(pos_) + ")",
                  ErrorContext{file_, 0, ""});
    const int line = 1 + static_cast<int>(std::count(t_.begin(), t_.begin() + pos_, '\n'));
    throw Error(section + ": " + what, ErrorContext{file_, line, ""});
  }

  /// @return true when only whitespace is left
  bool atEnd() {
    skipSpace();
    return pos_ >= t_.size();
  }
  /// @return bytes left
  std::size_t remaining() const { return t_.size() - pos_; }
  /// Marks whether the bytes that follow are binary data (for messages).
  void data(bool on) { inData_ = on; }

  /// @return the next line without its end (after skipping blank lines)
  std::string line() {
    skipSpace();
    const std::size_t end = std::min(t_.find('\n', pos_), t_.size());
    std::string s = t_.substr(pos_, end - pos_);
    if (!s.empty() && s.back() == '\r')
      s.pop_back();
    pos_ = std::min(end + 1, t_.size());
    return s;
  }
  /// Skips to just after the end of the current line (MSH 2.2 binary data
  /// starts there).
  void endLine() {
    while (pos_ < t_.size() && (t_[pos_] == ' ' || t_[pos_] == '\t' || t_[pos_] == '\r'))
      ++pos_;
    if (pos_ >= t_.size() || t_[pos_] != '\n')
      fail("expected the end of the line");
    ++pos_;
  }
  /// Requires the line `$End<name>` of the current section next.
  void expectEnd() {
    const std::string want = "$End" + section.substr(1);
    inData_ = false;
    const std::string got = line();
    if (got != want)
      fail("expected " + want + " after the counted entries, got '" + got.substr(0, 40) +
           "' (a count or an entry does not match the data)");
  }

  /// @return an integer in [@p lo, @p hi] stored as @p field; @p what names it
  long long integer(Field field, const Label& what, long long lo, long long hi) {
    long long v = 0;
    if (binary && field == Field::kInt) {
      v = take<std::int32_t>(what);
    } else if (binary && field == Field::kSize) {
      const auto u = take<std::uint64_t>(what);
      if (u > static_cast<std::uint64_t>(hi))
        fail(what() + " is " + std::to_string(u) + ", more than " + std::to_string(hi));
      v = static_cast<long long>(u);
    } else {
      const std::string s = token(what);
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
      if (ec != std::errc() || end != s.data() + s.size())
        fail(what() + ": expected an integer, got '" + s.substr(0, 40) + "'");
    }
    if (v < lo || v > hi)
      fail(what() + " is " + std::to_string(v) + ", outside " + std::to_string(lo) + " to " +
           std::to_string(hi));
    return v;
  }
  /// A count of items of at least @p bytes each in the rest of the file
  /// (refused when it is larger than the file can hold).
  long long count(Field field, const Label& what, double bytes) {
    const long long n = integer(field, what, 0, std::numeric_limits<long long>::max() / 64);
    if (double(n) * bytes > double(remaining()))
      fail(what() + " is " + std::to_string(n) + ", more than the " + std::to_string(remaining()) +
           " bytes left in the file can hold");
    return n;
  }
  /// @return a finite coordinate (8-byte double in binary)
  double real(const Label& what) {
    double v = 0;
    if (binary) {
      v = take<double>(what);
    } else {
      const std::string s = token(what);
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
      if (ec != std::errc() || end != s.data() + s.size())
        fail(what() + ": expected a number, got '" + s.substr(0, 40) + "'");
    }
    if (!std::isfinite(v))
      fail(what() + " is not finite");
    return v;
  }
  /// @return the rest of the current line (ASCII)
  std::string restOfLine() {
    const std::size_t end = std::min(t_.find('\n', pos_), t_.size());
    std::string s = t_.substr(pos_, end - pos_);
    pos_ = std::min(end + 1, t_.size());
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
      s.pop_back();
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
      s.erase(s.begin());
    return s;
  }

private:
  void skipSpace() {
    while (pos_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[pos_])))
      ++pos_;
  }
  std::string token(const Label& what) {
    skipSpace();
    const std::size_t start = pos_;
    while (pos_ < t_.size() && !std::isspace(static_cast<unsigned char>(t_[pos_])))
      ++pos_;
    if (start == pos_)
      fail("the file ends before " + what());
    return t_.substr(start, std::min<std::size_t>(pos_ - start, 64));
  }
  template <typename T>
  T take(const Label& what) {
    if (remaining() < sizeof(T))
      fail("the file ends before " + what());
    T v;
    std::memcpy(&v, t_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }

  const std::string& t_;
  const std::string& file_;
  std::size_t pos_ = 0;
  bool inData_ = false;
};

/// The whole check: MeshFormat first, then the sections in any order that
/// MSH allows ($Entities before $Nodes before $Elements).
class MshChecker {
public:
  MshChecker(const std::string& text, const std::string& file) : c_(text, file) {}

  void run() {
    if (c_.line() != "$MeshFormat")
      c_.fail("the file does not start with $MeshFormat (not a gmsh .msh file)");
    meshFormat();
    std::unordered_set<std::string> seen;
    while (!c_.atEnd()) {
      const std::string head = c_.line();
      c_.section = head.substr(0, 40);
      if (head.empty() || head[0] != '$')
        c_.fail("expected a section ($Name), got '" + head.substr(0, 40) + "'");
      if (!seen.insert(head).second)
        c_.fail("the section appears twice");
      if (head == "$PhysicalNames") {
        physicalNames();
      } else if (head == "$Entities" && version_ == 4) {
        entities();
      } else if (head == "$Nodes") {
        version_ == 4 ? nodes41() : nodes22();
      } else if (head == "$Elements") {
        if (!seen.count("$Nodes"))
          c_.fail("$Elements comes before $Nodes");
        version_ == 4 ? elements41() : elements22();
      } else if (head == "$Comments") {
        while (c_.line() != "$EndComments")
          if (c_.atEnd())
            c_.fail("the file ends before $EndComments");
        continue;
      } else {
        c_.fail("section not read by lamina (a .msh file may hold $MeshFormat, "
                "$PhysicalNames, $Entities (4.1), $Nodes, $Elements and $Comments)");
      }
      c_.expectEnd();
    }
    c_.section = "file";
    if (!seen.count("$Nodes") || !seen.count("$Elements"))
      c_.fail("a mesh needs both $Nodes and $Elements");
  }

private:
  void meshFormat() {
    const std::string version = c_.restOfLine().substr(0, 40);
    std::istringstream in(version);
    std::string v, type, size;
    in >> v >> type >> size;
    if (v != "4.1" && v != "2.2")
      c_.fail("version '" + v + "': lamina reads MSH 2.2 and 4.1 (gmsh -format msh41 or msh22)");
    if ((type != "0" && type != "1") || size != "8")
      c_.fail("expected '" + v + " 0 8' (ASCII) or '" + v + " 1 8' (binary), got '" + version +
              "'");
    version_ = v == "4.1" ? 4 : 2;
    if (type == "1") {
      c_.binary = true;
      c_.data(true);
      if (c_.integer(Field::kInt, "the byte-order mark", std::numeric_limits<int>::min(),
                     std::numeric_limits<int>::max()) != 1)
        c_.fail("the byte-order mark is not 1 (written on a machine of the other byte order?)");
    }
    c_.expectEnd();
  }

  void physicalNames() {
    const bool bin = c_.binary;
    c_.binary = false; // always text
    const long long n = c_.count(Field::kText, "the number of names", 8);
    for (long long i = 0; i < n; ++i) {
      const auto which = [&] { return "name " + std::to_string(i + 1); };
      c_.integer(Field::kText, join(which, ": dimension"), 0, 3);
      c_.integer(Field::kText, join(which, ": tag"), -kMaxTag, kMaxTag);
      const std::string name = c_.restOfLine();
      if (name.size() < 2 || name.front() != '"' || name.back() != '"' || name.size() > 130)
        c_.fail(which() + ": expected a quoted name of at most 128 characters");
    }
    c_.binary = bin;
  }

  void entities() {
    c_.data(c_.binary);
    std::array<long long, 4> n{};
    for (int d = 0; d < 4; ++d)
      n[d] = c_.count(Field::kSize, "the number of entities of dimension " + std::to_string(d), 8);
    for (int d = 0; d < 4; ++d)
      for (long long i = 0; i < n[d]; ++i) {
        const auto which = [&] {
          return "entity " + std::to_string(i + 1) + " of dimension " + std::to_string(d);
        };
        const long long tag = c_.integer(Field::kInt, join(which, ": tag"), 1, kMaxTag);
        for (int k = 0; k < (d == 0 ? 3 : 6); ++k)
          c_.real(join(which, ": coordinate"));
        const long long phys = c_.count(Field::kSize, join(which, ": number of physical tags"), 2);
        for (long long k = 0; k < phys; ++k)
          c_.integer(Field::kInt, join(which, ": physical tag"), -kMaxTag, kMaxTag);
        if (d > 0) {
          const long long bound =
              c_.count(Field::kSize, join(which, ": number of bounding entities"), 2);
          for (long long k = 0; k < bound; ++k) {
            const long long b =
                c_.integer(Field::kInt, join(which, ": bounding entity"), -kMaxTag, kMaxTag);
            if (!entities_[d - 1].count(std::llabs(b)))
              c_.fail(which() + " is bounded by entity " + std::to_string(b) +
                      ", which is not an entity of dimension " + std::to_string(d - 1));
          }
        }
        if (!entities_[d].insert(tag).second)
          c_.fail(which() + ": tag " + std::to_string(tag) + " appears twice");
      }
    has_entities_ = true;
  }

  /// An entity block's (dim, tag): the entity must be declared in $Entities.
  void requireEntity(int dim, long long tag, const Label& which) {
    if (has_entities_ && !entities_[dim].count(tag))
      c_.fail(which() + " names entity " + std::to_string(tag) + " of dimension " +
              std::to_string(dim) + ", which $Entities does not declare");
  }

  /// The tags of one kind are unique (sorted in place).
  void requireUnique(std::vector<long long>& tags, const char* kind) {
    std::sort(tags.begin(), tags.end());
    const auto twice = std::adjacent_find(tags.begin(), tags.end());
    if (twice != tags.end())
      c_.fail(std::string(kind) + " tag " + std::to_string(*twice) + " appears twice");
  }

  /// Header of $Nodes or $Elements (4.1): blocks, items, min and max tag.
  struct Header {
    long long blocks, items, min, max;
  };
  Header header41(const char* kind, double bytes_per_item) {
    c_.data(c_.binary);
    Header h{};
    h.blocks = c_.count(Field::kSize, "the number of blocks", c_.binary ? 20 : 8);
    h.items = c_.count(Field::kSize, std::string("the number of ") + kind + "s", bytes_per_item);
    h.min = c_.integer(Field::kSize, std::string("the smallest ") + kind + " tag", 0, kMaxTag);
    h.max = c_.integer(Field::kSize, std::string("the largest ") + kind + " tag", 0, kMaxTag);
    if (h.items > 0 && (h.min < 1 || h.min > h.max))
      c_.fail(std::string("the ") + kind + " tag range " + std::to_string(h.min) + " to " +
              std::to_string(h.max) + " is not a range of positive tags");
    return h;
  }

  void nodes41() {
    const Header h = header41("node", c_.binary ? 32 : 8);
    long long total = 0;
    nodes_.reserve(static_cast<std::size_t>(h.items));
    for (long long b = 0; b < h.blocks; ++b) {
      const auto which = [&] { return "node block " + std::to_string(b + 1); };
      const int dim = static_cast<int>(c_.integer(Field::kInt, join(which, ": dimension"), 0, 3));
      requireEntity(dim, c_.integer(Field::kInt, join(which, ": entity tag"), 1, kMaxTag), which);
      const int parametric =
          static_cast<int>(c_.integer(Field::kInt, join(which, ": parametric"), 0, 1));
      const int reals = 3 + parametric * dim;
      const long long n = c_.count(Field::kSize, join(which, ": number of nodes"),
                                   (1 + reals) * (c_.binary ? 8.0 : 2.0));
      if (n > h.items - total)
        c_.fail(which() + " holds more nodes than the header's " + std::to_string(h.items));
      total += n;
      for (long long k = 0; k < n; ++k)
        nodes_.push_back(c_.integer(Field::kSize, join(which, ": node tag"), h.min, h.max));
      for (long long k = 0; k < n * reals; ++k)
        c_.real([&] {
          return which() + ": coordinate of node " +
                 std::to_string(nodes_[nodes_.size() - n + k / reals]);
        });
    }
    if (total != h.items)
      c_.fail("the blocks hold " + std::to_string(total) + " nodes, the header says " +
              std::to_string(h.items));
    requireUnique(nodes_, "node");
    indexNodes();
  }

  /// @return the node count of element type @p type of an element of dimension @p dim
  int nodesOf(long long type, int dim, const Label& which) {
    if (type < 1 || type >= static_cast<long long>(kShapes.size()))
      c_.fail(which() + ": element type " + std::to_string(type) +
              " is not one lamina checks (types 1 to 31: points, lines, triangles, "
              "quadrangles and the 3D types, orders 1 to 3)");
    if (dim >= 0 && kShapes[type].dim != dim)
      c_.fail(which() + ": element type " + std::to_string(type) + " has dimension " +
              std::to_string(kShapes[type].dim) + ", its entity " + std::to_string(dim));
    return kShapes[type].nodes;
  }

  /// Marks the node tags in a table by tag when their range is dense (gmsh
  /// numbers nodes 1 to n), so hasNode needs no search: under 64 slots a
  /// node, 1 bit each, less memory than nodes_ itself; else hasNode searches.
  void indexNodes() {
    const auto n = static_cast<long long>(nodes_.size());
    if (nodes_.empty() || nodes_.back() - nodes_.front() >= 64 * n + 1024)
      return;
    first_node_ = nodes_.front();
    node_present_.assign(static_cast<std::size_t>(nodes_.back() - first_node_ + 1), false);
    for (long long t : nodes_)
      node_present_[static_cast<std::size_t>(t - first_node_)] = true;
  }
  /// @return whether $Nodes defines node @p t
  bool hasNode(long long t) const {
    if (node_present_.empty())
      return std::binary_search(nodes_.begin(), nodes_.end(), t);
    return t >= first_node_ && t - first_node_ < static_cast<long long>(node_present_.size()) &&
           node_present_[static_cast<std::size_t>(t - first_node_)];
  }

  /// Reads @p nn node tags of element @p which and requires each in $Nodes.
  void elementNodes(int nn, Field field, const Label& which) {
    for (int k = 0; k < nn; ++k) {
      const long long t = c_.integer(field, join(which, ": node tag"), 1, kMaxTag);
      if (!hasNode(t))
        c_.fail(which() + " refers to node " + std::to_string(t) +
                ", which $Nodes does not define");
    }
  }

  void elements41() {
    const Header h = header41("element", c_.binary ? 16 : 4);
    long long total = 0;
    std::vector<long long> tags;
    tags.reserve(static_cast<std::size_t>(h.items));
    for (long long b = 0; b < h.blocks; ++b) {
      const auto block = [&] { return "element block " + std::to_string(b + 1); };
      const int dim = static_cast<int>(c_.integer(Field::kInt, join(block, ": dimension"), 0, 3));
      requireEntity(dim, c_.integer(Field::kInt, join(block, ": entity tag"), 1, kMaxTag), block);
      const int nn =
          nodesOf(c_.integer(Field::kInt, join(block, ": element type"), 0, kMaxTag), dim, block);
      const long long n = c_.count(Field::kSize, join(block, ": number of elements"),
                                   c_.binary ? 8.0 * (1 + nn) : 2.0 * (1 + nn));
      if (n > h.items - total)
        c_.fail(block() + " holds more elements than the header's " + std::to_string(h.items));
      total += n;
      for (long long k = 0; k < n; ++k) {
        const long long tag = c_.integer(Field::kSize, join(block, ": element tag"), h.min, h.max);
        tags.push_back(tag);
        elementNodes(nn, Field::kSize,
                     [&] { return "element " + std::to_string(tag) + " (" + block() + ")"; });
      }
    }
    if (total != h.items)
      c_.fail("the blocks hold " + std::to_string(total) + " elements, the header says " +
              std::to_string(h.items));
    requireUnique(tags, "element");
  }

  void nodes22() {
    const long long n = c_.count(Field::kText, "the number of nodes", c_.binary ? 28 : 8);
    if (c_.binary)
      c_.endLine();
    c_.data(c_.binary);
    nodes_.reserve(static_cast<std::size_t>(n));
    for (long long k = 0; k < n; ++k) {
      nodes_.push_back(c_.integer(Field::kInt, "node tag", 1, kMaxTag));
      for (int j = 0; j < 3; ++j)
        c_.real([&] { return "coordinate of node " + std::to_string(nodes_.back()); });
    }
    requireUnique(nodes_, "node");
    indexNodes();
  }

  /// One element of MSH 2.2 after its type and tag count: its tags
  /// (physical, elementary, then partitions: their count first) and nodes.
  void element22(int nn, long long ntags, const Label& which) {
    long long partitions = 0; // the third tag
    for (long long k = 0; k < ntags; ++k) {
      const long long t = c_.integer(Field::kInt, join(which, ": tag"), -kMaxTag, kMaxTag);
      if (k == 2)
        partitions = t;
    }
    if (ntags > 2 && partitions != ntags - 3)
      c_.fail(which() + ": " + std::to_string(ntags) + " tags but a partition count of " +
              std::to_string(partitions));
    elementNodes(nn, Field::kInt, which);
  }

  void elements22() {
    const long long n = c_.count(Field::kText, "the number of elements", 8);
    if (c_.binary)
      c_.endLine();
    c_.data(c_.binary);
    std::vector<long long> tags;
    tags.reserve(static_cast<std::size_t>(n));
    long long read = 0;
    while (read < n) {
      if (c_.binary) { // a header: type, how many follow, tag count; then the elements
        const long long type = c_.integer(Field::kInt, "element type", 0, kMaxTag);
        const int nn = nodesOf(type, -1, "element header");
        const long long follow = c_.integer(Field::kInt, "elements in the header", 1, n - read);
        const long long ntags = c_.integer(Field::kInt, "tag count", 0, 64);
        if (double(follow) * 4 * (1 + ntags + nn) > double(c_.remaining()))
          c_.fail(std::to_string(follow) + " elements are more than the rest of the file holds");
        for (long long k = 0; k < follow; ++k) {
          tags.push_back(c_.integer(Field::kInt, "element tag", 1, kMaxTag));
          element22(nn, ntags, [&] { return "element " + std::to_string(tags.back()); });
        }
        read += follow;
      } else {
        tags.push_back(c_.integer(Field::kInt, "element tag", 1, kMaxTag));
        const long long tag = tags.back();
        const auto which = [&] { return "element " + std::to_string(tag); };
        const int nn =
            nodesOf(c_.integer(Field::kInt, join(which, ": type"), 0, kMaxTag), -1, which);
        element22(nn, c_.integer(Field::kInt, join(which, ": tag count"), 0, 64), which);
        ++read;
      }
    }
    requireUnique(tags, "element");
  }

  Cursor c_;
  int version_ = 4;
  std::array<std::unordered_set<long long>, 4> entities_;
  bool has_entities_ = false;
  std::vector<long long> nodes_;   ///< node tags, sorted once $Nodes is read
  std::vector<bool> node_present_; ///< by tag - first_node_ (indexNodes), or empty
  long long first_node_ = 0;       ///< the smallest node tag when node_present_ is used
};

} // namespace

void checkMshText(const std::string& text, const std::string& file) {
  MshChecker(text, file).run();
}

void checkMshFile(const std::filesystem::path& path) {
  const std::string file = path.string();
  checkMshText(core::readWholeFile(path, core::kMaxMeshBytes, "mesh file"), file);
}

} // namespace lamina::membrane
