#pragma once
/// @file test_util.hpp
/// @brief Helpers shared by the core and materials test suites: a temporary
/// directory, whole-file reads and writes, the message of a lamina::Error and
/// repeated text, inputs that are not regular files and a guard against a
/// hang (hostile-input tests of several stages include it).

#include "core/error.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>
#include <vector>
#include <string>

namespace lamina::test {

/// A fresh directory under the system temporary directory, removed with its
/// content when the object dies.
class TempDir {
public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "lamina-test-XXXXXX").string();
    if (!::mkdtemp(tmpl.data()))
      throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// @return the directory
  const std::filesystem::path& path() const { return path_; }
  /// @return the path of @p name inside the directory
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

/// @return the whole content of @p path ("" if it does not exist)
inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Writes @p text to @p path (plain write: test set-up only).
inline void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// @return what() of the lamina::Error thrown by @p f, "" if none is thrown
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

/// @return @p s repeated @p n times (deep nesting, long keys)
inline std::string repeat(const std::string& s, int n) {
  std::string out;
  out.reserve(s.size() * static_cast<std::size_t>(n > 0 ? n : 0));
  for (int i = 0; i < n; ++i)
    out += s;
  return out;
}

/// Kills the test process (SIGALRM) when it is still running after
/// @p seconds: a reader that blocks on a FIFO fails its test instead of
/// hanging the suite until the CTest timeout.
class HangGuard {
public:
  explicit HangGuard(unsigned seconds) { ::alarm(seconds); }
  ~HangGuard() { ::alarm(0); }
  HangGuard(const HangGuard&) = delete;
  HangGuard& operator=(const HangGuard&) = delete;
};

/// Creates, in @p dir, inputs named "NAME@p suffix" that are not regular
/// files: a FIFO with no writer, a directory, a Unix socket, a symlink to
/// /dev/null and a symlink to the FIFO. @return their paths.
inline std::vector<std::filesystem::path> notRegularFiles(const TempDir& dir,
                                                          const std::string& suffix) {
  const auto fifo = dir / ("fifo" + suffix), folder = dir / ("folder" + suffix),
             socket = dir / ("socket" + suffix), null = dir / ("devnull" + suffix),
             to_fifo = dir / ("to-fifo" + suffix);
  if (::mkfifo(fifo.c_str(), 0600) != 0)
    throw std::runtime_error("mkfifo failed");
  std::filesystem::create_directory(folder);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string s = socket.string();
  if (fd < 0 || s.size() >= sizeof addr.sun_path)
    throw std::runtime_error("cannot create a socket");
  s.copy(addr.sun_path, s.size());
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    throw std::runtime_error("cannot bind a socket");
  ::close(fd); // the socket file stays
  std::filesystem::create_symlink("/dev/null", null);
  std::filesystem::create_symlink(fifo, to_fifo);
  return {fifo, folder, socket, null, to_fifo};
}

} // namespace lamina::test
