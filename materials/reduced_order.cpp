#include "materials/reduced_order.hpp"

#include "core/error.hpp"
#include "core/hdf5_file.hpp"

#include <cmath>
#include <sstream>

namespace lamina::materials {

namespace {

constexpr const char* kFormat = "lamina-reduced-order-cell 1";
/// a clustering cell: format 1 plus /Ga, /Gb and "scheme"
constexpr const char* kFormatClustering = "lamina-reduced-order-cell 2";

using Dims = std::vector<std::uint64_t>;

template <class M>
bool finite(const M& m) {
  return m.allFinite();
}

/// Row-major copy of @p count 6x6 matrices.
std::vector<double> flatten(const std::vector<Matrix6>& ms) {
  std::vector<double> out;
  out.reserve(36 * ms.size());
  for (const Matrix6& m : ms)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        out.push_back(m(i, j));
  return out;
}

std::vector<double> flatten(const Eigen::MatrixXd& m) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(m.size()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      out.push_back(m(i, j));
  return out;
}

/// Reads dataset @p name of shape @p expect (doubles), naming file and dataset on a mismatch.
std::vector<double> readShaped(const core::H5File& f, const std::string& name, const Dims& expect) {
  Dims dims;
  std::vector<double> v = f.readDoubles(name, dims);
  if (dims != expect) {
    std::ostringstream os;
    os << f.path().string() << ": dataset " << name << " has shape (";
    for (std::size_t i = 0; i < dims.size(); ++i)
      os << (i ? ", " : "") << dims[i];
    os << "), expected (";
    for (std::size_t i = 0; i < expect.size(); ++i)
      os << (i ? ", " : "") << expect[i];
    os << ")";
    throw Error(os.str());
  }
  return v;
}

std::vector<Matrix6> matrices(const std::vector<double>& v) {
  std::vector<Matrix6> out(v.size() / 36);
  for (std::size_t k = 0; k < out.size(); ++k)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        out[k](i, j) = v[36 * k + static_cast<std::size_t>(6 * i + j)];
  return out;
}

Eigen::MatrixXd matrix(const std::vector<double>& v, Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j)
      m(i, j) = v[static_cast<std::size_t>(i * cols + j)];
  return m;
}

} // namespace

const char* toString(ReducedOrderScheme scheme) {
  return kReducedOrderSchemeNames.name(scheme).data(); // literals: NUL-terminated
}

std::vector<int> ReducedOrderModel::partitionsPerPhase() const {
  std::vector<int> count(phases.size(), 0);
  for (std::int32_t p : partition_phase)
    ++count[static_cast<std::size_t>(p)];
  return count;
}

Matrix6 ReducedOrderModel::referenceStiffness(const std::vector<Stiffness>& L0) const {
  Matrix6 C = Matrix6::Zero();
  for (std::size_t b = 0; b < A.size(); ++b)
    C += fraction[b] * L0[static_cast<std::size_t>(partition_phase[b])].matrix() * A[b];
  return 0.5 * (C + C.transpose());
}

void ReducedOrderModel::validate(const std::string& where) const {
  const int n = partitions();
  const auto un = static_cast<std::size_t>(n);
  LAMINA_CHECK(n >= 1, where, ": a reduced-order cell needs at least one partition");
  LAMINA_CHECK(!phases.empty(), where, ": a reduced-order cell needs at least one phase");
  LAMINA_CHECK(partition_phase.size() == un && A.size() == un && P.size() == un * un, where, ": ",
               n, " partitions but ", partition_phase.size(), " phase indices, ", A.size(),
               " A and ", P.size(), " P matrices (expected ", n, ", ", n, ", ", n * n, ")");
  LAMINA_CHECK(R.rows() == 6 * n && R.cols() == 6 * n && Q.rows() == 6 && Q.cols() == 6 * n, where,
               ": R must be ", 6 * n, " x ", 6 * n, " and Q 6 x ", 6 * n);
  double sum = 0;
  for (std::size_t a = 0; a < un; ++a) {
    const std::int32_t p = partition_phase[a];
    LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < phases.size(), where, ": partition ", a,
                 " names phase ", p, " of ", phases.size());
    LAMINA_CHECK(std::isfinite(fraction[a]) && fraction[a] > 0 && fraction[a] <= 1, where,
                 ": partition ", a, " has volume fraction ", fraction[a], " (must be in (0, 1])");
    LAMINA_CHECK(finite(A[a]), where, ": A of partition ", a, " is not finite");
    sum += fraction[a];
  }
  LAMINA_CHECK(std::abs(sum - 1) <= 1e-12, where, ": the partition fractions sum to ", sum,
               ", not 1");
  for (std::size_t k = 0; k < P.size(); ++k)
    LAMINA_CHECK(finite(P[k]), where, ": P of partitions (", k / un, ", ", k % un,
                 ") is not finite");
  const bool clustering = scheme == ReducedOrderScheme::Clustering;
  LAMINA_CHECK(Ga.size() == (clustering ? un * un : 0) && Gb.size() == Ga.size(), where, ": ",
               clustering ? "a clustering cell needs " : "a cell of scheme tfa has ",
               clustering ? n * n : 0, " Ga and Gb matrices, not ", Ga.size(), " and ", Gb.size());
  for (std::size_t k = 0; k < Ga.size(); ++k)
    LAMINA_CHECK(finite(Ga[k]) && finite(Gb[k]), where, ": Ga or Gb of partitions (", k / un, ", ",
                 k % un, ") is not finite");
  LAMINA_CHECK(finite(R) && finite(Q) && finite(D_lin) && finite(C), where,
               ": R, Q, D_lin and C must be finite");
  LAMINA_CHECK(std::isfinite(density) && density > 0, where, ": density ", density,
               " must be positive");
}

void writeReducedOrderArrays(const std::filesystem::path& path, const ReducedOrderModel& m) {
  m.validate(path.string());
  const auto n = static_cast<std::uint64_t>(m.partitions());
  core::H5File f(path, core::H5File::Mode::Create);
  const bool clustering = m.scheme == ReducedOrderScheme::Clustering;
  f.writeAttribute("/", "format", clustering ? kFormatClustering : kFormat);
  if (clustering) {
    f.writeAttribute("/", "scheme", toString(m.scheme));
    f.writeDoubles("/Ga", flatten(m.Ga).data(), {n, n, 6, 6});
    f.writeDoubles("/Gb", flatten(m.Gb).data(), {n, n, 6, 6});
  }
  f.writeInts("/partition_phase", m.partition_phase.data(), {n});
  f.writeDoubles("/fraction", m.fraction.data(), {n});
  f.writeDoubles("/A", flatten(m.A).data(), {n, 6, 6});
  f.writeDoubles("/P", flatten(m.P).data(), {n, n, 6, 6});
  f.writeDoubles("/R", flatten(m.R).data(), {6 * n, 6 * n});
  f.writeDoubles("/Q", flatten(m.Q).data(), {6, 6 * n});
  f.writeDoubles("/D_lin", flatten(Eigen::MatrixXd(m.D_lin)).data(), {6, 6});
  f.writeDoubles("/C", flatten(Eigen::MatrixXd(m.C)).data(), {6, 6});
  f.writeDoubles("/density", &m.density, {1});
  f.flush();
}

void readReducedOrderArrays(const std::filesystem::path& path, ReducedOrderModel& m) {
  const core::H5File f(path, core::H5File::Mode::ReadOnly);
  std::string format;
  try {
    format = f.readStringAttribute("/", "format");
  } catch (const Error&) {
    format.clear();
  }
  LAMINA_CHECK(format == kFormat || format == kFormatClustering, path.string(),
               ": not a reduced-order cell file (attribute 'format' is '", format, "', expected '",
               kFormat, "' or '", kFormatClustering, "')");
  m.scheme = ReducedOrderScheme::Transformation;
  if (format == kFormatClustering) {
    std::string scheme;
    try {
      scheme = f.readStringAttribute("/", "scheme");
    } catch (const Error&) {
      scheme = "(missing)";
    }
    // format 2 is a clustering cell, and its attribute says so
    LAMINA_CHECK(kReducedOrderSchemeNames.parse(scheme) == ReducedOrderScheme::Clustering,
                 path.string(), ": format '", kFormatClustering,
                 "' is a clustering cell, but its "
                 "attribute 'scheme' is '",
                 scheme, "'");
    m.scheme = ReducedOrderScheme::Clustering;
  }
  Dims dims;
  m.partition_phase = f.readInts("/partition_phase", dims);
  // 4096 partitions: R alone is then 1.2 GB, and every index (beta n +
  // alpha, 6 n) stays far inside an int
  LAMINA_CHECK(dims.size() == 1 && dims[0] >= 1 && dims[0] <= 4096u, path.string(),
               ": dataset /partition_phase must list 1 to 4096 partitions");
  const std::uint64_t n = dims[0];
  const auto in = static_cast<Eigen::Index>(n);
  m.fraction = readShaped(f, "/fraction", {n});
  m.A = matrices(readShaped(f, "/A", {n, 6, 6}));
  m.P = matrices(readShaped(f, "/P", {n, n, 6, 6}));
  m.R = matrix(readShaped(f, "/R", {6 * n, 6 * n}), 6 * in, 6 * in);
  m.Q = matrix(readShaped(f, "/Q", {6, 6 * n}), 6, 6 * in);
  m.Ga.clear();
  m.Gb.clear();
  if (m.scheme == ReducedOrderScheme::Clustering) {
    m.Ga = matrices(readShaped(f, "/Ga", {n, n, 6, 6}));
    m.Gb = matrices(readShaped(f, "/Gb", {n, n, 6, 6}));
  }
  m.D_lin = matrix(readShaped(f, "/D_lin", {6, 6}), 6, 6);
  m.C = matrix(readShaped(f, "/C", {6, 6}), 6, 6);
  m.density = readShaped(f, "/density", {1})[0];
  m.validate(path.string());
}

} // namespace lamina::materials
