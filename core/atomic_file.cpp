#include "core/atomic_file.hpp"

#include "core/error.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lamina::core {

namespace {
[[noreturn]] void sysFail(const std::string& what, const std::filesystem::path& p) {
  throw Error(what + ": " + std::strerror(errno), {p.string(), 0, ""});
}

void fsyncDirectory(const std::filesystem::path& file) {
  std::filesystem::path dir = file.parent_path();
  if (dir.empty())
    dir = ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}
} // namespace

void writeFileAtomically(const std::filesystem::path& path, const std::string& content) {
  const std::filesystem::path dir = path.parent_path();
  if (!dir.empty())
    std::filesystem::create_directories(dir);
  std::string tmpl = path.string() + ".tmp.XXXXXX";
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0)
    sysFail("cannot create temporary file", path);
  const std::filesystem::path tmp = tmpl;
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR)
        continue;
      ::close(fd);
      std::filesystem::remove(tmp);
      sysFail("cannot write", tmp);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0) {
    ::close(fd);
    std::filesystem::remove(tmp);
    sysFail("cannot sync", tmp);
  }
  ::close(fd);
  renameIntoPlace(tmp, path);
}

void renameIntoPlace(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (::rename(from.c_str(), to.c_str()) != 0) {
    std::error_code ec;
    std::filesystem::remove(from, ec);
    sysFail("cannot rename into place", to);
  }
  fsyncDirectory(to);
}

FileLock::FileLock(const std::filesystem::path& path) {
  const std::filesystem::path lock = path.string() + ".lock";
  if (!lock.parent_path().empty())
    std::filesystem::create_directories(lock.parent_path());
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
  if (fd_ < 0)
    sysFail("cannot open lock file", lock);
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno != EINTR) {
      ::close(fd_);
      sysFail("cannot lock", lock);
    }
  }
}

FileLock::~FileLock() {
  if (fd_ >= 0) {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
}

} // namespace lamina::core
