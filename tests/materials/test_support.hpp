#pragma once
/// @file test_support.hpp
/// @brief Helpers shared by the materials test suites: temporary directories,
/// random SPD stiffnesses and rotations, relative differences, and running the
/// `materials` program as a child process.

#include "../core/test_util.hpp"
#include "materials/law.hpp"
#include "materials/stiffness.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace lamina::test {

/// Table 1 of the membrane paper, typed in from the paper (GPa -> Pa, lamina
/// order: c44 = xy, c55 = yz, c66 = xz, zeros elsewhere).
inline materials::Matrix6 membranePaperTable1() {
  const double GPa = 1e9;
  materials::Matrix6 c = materials::Matrix6::Zero();
  c(0, 0) = 150 * GPa;
  c(0, 1) = c(1, 0) = 40 * GPa;
  c(0, 2) = c(2, 0) = 10 * GPa;
  c(1, 1) = 150 * GPa;
  c(1, 2) = c(2, 1) = 80 * GPa;
  c(2, 2) = 150 * GPa;
  c(3, 3) = 80 * GPa;
  c(4, 4) = 20 * GPa;
  c(5, 5) = 30 * GPa;
  return c;
}

/// A random symmetric positive definite 6x6 matrix with no zero pattern
/// (triclinic), entries of order 1e10 Pa: A A^T + 2 I scaled, A uniform in (-1, 1).
inline materials::Matrix6 randomSpd(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  materials::Matrix6 a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      a(i, j) = u(rng);
  materials::Matrix6 c = a * a.transpose() + 2.0 * materials::Matrix6::Identity();
  c = 0.5 * (c + c.transpose()).eval();
  return 1e10 * c;
}

/// A random proper rotation (normalized random quaternion).
inline Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// @return max |a - b| / max |b| (0 when both vanish)
inline double relDiff(const materials::Matrix6& a, const materials::Matrix6& b) {
  const double scale = b.cwiseAbs().maxCoeff();
  const double d = (a - b).cwiseAbs().maxCoeff();
  return scale > 0 ? d / scale : d;
}

/// Rotates the fourth-order tensor by definition,
/// C'_ijkl = R_ip R_jq R_kr R_ls C_pqrs, going through the full 3x3x3x3 array
/// (the oracle for Stiffness::rotated). With engineering shear strain,
/// C_ijkl equals the lamina entry of the pairs (xx yy zz xy yz xz).
inline materials::Matrix6 rotateByDefinition(const materials::Matrix6& c,
                                             const Eigen::Matrix3d& r) {
  const int idx[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
  double t[3][3][3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          t[i][j][k][l] = c(idx[i][j], idx[k][l]);
  materials::Matrix6 out = materials::Matrix6::Zero();
  const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int i = pairs[a][0], j = pairs[a][1], k = pairs[b][0], l = pairs[b][1];
      double s = 0;
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
          for (int u = 0; u < 3; ++u)
            for (int v = 0; v < 3; ++v)
              s += r(i, p) * r(j, q) * r(k, u) * r(l, v) * t[p][q][u][v];
      out(a, b) = s;
    }
  return out;
}

/// Central differences of @p law's update() from @p state_n in the strain at
/// t_{n+1}, step @p h (everything else of @p step held, J included, as the
/// laws' tangents hold it): the oracle of consistent tangents.
inline materials::Matrix6 centralDifferenceTangent(const materials::ConstitutiveLaw& law,
                                                   const materials::PointStep& step,
                                                   const double* state_n, double h) {
  std::vector<double> out(static_cast<std::size_t>(law.stateSize()));
  materials::Matrix6 T;
  for (int j = 0; j < 6; ++j) {
    materials::PointStep sp = step, sm = step;
    sp.eps[j] += h;
    sm.eps[j] -= h;
    materials::Vector6 a, b;
    law.update(sp, state_n, out.data(), a, nullptr);
    law.update(sm, state_n, out.data(), b, nullptr);
    T.col(j) = (a - b) / (2 * h);
  }
  return T;
}

/// Result of running a program.
struct RunResult {
  int status = -1; ///< exit code (-1 if it did not exit normally)
  std::string out; ///< its standard output
  std::string err; ///< its standard error
};

/// Path of the `materials` program of this build.
inline std::string materialsProgram() {
  return std::string(LAMINA_BINARY_DIR) + "/bin/materials";
}

/// Path of the source tree's catalog.
inline std::string catalogPath() {
  return std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml";
}

/// Runs `materials --library LIB --catalog CATALOG ARGS` through the shell,
/// capturing stdout and stderr in files of @p dir. Arguments must not need
/// quoting beyond single quotes (test paths and names are plain).
inline RunResult runMaterials(const TempDir& dir, const std::filesystem::path& library,
                              const std::string& args) {
  static int counter = 0;
  const std::string tag = std::to_string(counter++);
  const auto out = dir / ("stdout." + tag), err = dir / ("stderr." + tag);
  const std::string cmd = "'" + materialsProgram() + "' --library '" + library.string() +
                          "' --catalog '" + catalogPath() + "' " + args + " > '" + out.string() +
                          "' 2> '" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = readFile(out);
  r.err = readFile(err);
  return r;
}

/// The numeric rows of CSV file @p path after its header line (returned in
/// @p header when not null); every cell parsed with std::stod.
inline std::vector<std::vector<double>> readCsvRows(const std::filesystem::path& path,
                                                    std::string* header = nullptr) {
  std::istringstream in(readFile(path));
  std::string line;
  std::getline(in, line);
  if (header)
    *header = line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream items(line);
    for (std::string item; std::getline(items, item, ',');)
      v.push_back(std::stod(item));
    rows.push_back(v);
  }
  return rows;
}

/// Number of lines of @p text ('\n'-terminated; a trailing partial line counts).
inline int lineCount(const std::string& text) {
  int n = 0;
  for (char ch : text)
    n += ch == '\n';
  if (!text.empty() && text.back() != '\n')
    ++n;
  return n;
}

/// Runs @p body in a forked child process and returns at once in the parent.
/// The child exits 0 when @p body returns and 1 when it throws (the tests of
/// concurrent library writers and of writers killed mid-write).
/// @return the child's pid
inline pid_t forkChild(const std::function<void()>& body) {
  const pid_t pid = ::fork();
  if (pid < 0)
    throw std::runtime_error("fork failed");
  if (pid == 0) {
    int rc = 0;
    try {
      body();
    } catch (...) {
      rc = 1;
    }
    ::_exit(rc);
  }
  return pid;
}

/// Waits for every child in @p kids and expects each to have exited with 0.
inline void expectChildrenSucceed(const std::vector<pid_t>& kids) {
  for (pid_t pid : kids) {
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child " << pid;
  }
}

} // namespace lamina::test
