#include "core/atomic_file.hpp"
#include "core/input_file.hpp"

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

std::filesystem::path resolveLinks(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  for (int hops = 0;; ++hops) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(p, ec)))
      break;
    if (hops == 40)
      throw Error("too many levels of symbolic links", {path.string(), 0, ""});
    const std::filesystem::path target = std::filesystem::read_symlink(p);
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  // Links among the folders: resolve those that exist.
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::weakly_canonical(
      p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path(), ec);
  return ec ? p : dir / p.filename();
}

std::string temporaryPrefix(const std::filesystem::path& path) {
  return path.filename().string() + ".tmp.";
}

void checkReplaceable(const std::filesystem::path& path, const std::string& option) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) // absent, or a link to nothing yet
    return;
  if (!S_ISREG(st.st_mode))
    throw Error(std::string("refusing to write over ") + fileKindName(st.st_mode) +
                    ": an output replaces only a regular file",
                {path.string(), 0, option});
}

void checkOutputIsNotInput(const std::filesystem::path& out,
                           const std::vector<std::filesystem::path>& inputs,
                           const std::string& option) {
  for (const std::filesystem::path& in : inputs) {
    std::error_code ec;
    if (!in.empty() && std::filesystem::equivalent(out, in, ec) && !ec)
      throw Error("the output is an input of the run (" + in.string() +
                      "); refusing to overwrite it",
                  {out.string(), 0, option});
  }
}

void checkOutput(const std::filesystem::path& out, const std::vector<std::filesystem::path>& inputs,
                 const std::string& option) {
  checkReplaceable(out, option);
  checkOutputIsNotInput(out, inputs, option);
}

void writeFileAtomically(const std::filesystem::path& link, const std::string& content) {
  const std::filesystem::path path = resolveLinks(link);
  checkReplaceable(path);
  const std::filesystem::path dir = path.parent_path();
  if (!dir.empty())
    std::filesystem::create_directories(dir);
  struct stat old {};
  const mode_t mode = ::stat(path.c_str(), &old) == 0 ? (old.st_mode & 07777) : 0644;
  std::string tmpl = path.string() + ".tmp.XXXXXX";
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0)
    sysFail("cannot create temporary file", path);
  const std::filesystem::path tmp = tmpl;
  // On failure: close, remove the temporary, report the first errno.
  auto fail = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    errno = err;
    sysFail(what, tmp);
  };
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR)
        continue;
      fail("cannot write");
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fchmod(fd, mode) != 0 || ::fsync(fd) != 0)
    fail("cannot sync");
  if (::close(fd) != 0) {
    const int err = errno;
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    errno = err;
    sysFail("cannot close", tmp);
  }
  renameIntoPlace(tmp, path);
}

void renameIntoPlace(const std::filesystem::path& from, const std::filesystem::path& to) {
  try {
    checkReplaceable(to);
  } catch (const Error&) {
    std::error_code ec;
    std::filesystem::remove(from, ec);
    throw;
  }
  if (::rename(from.c_str(), to.c_str()) != 0) {
    std::error_code ec;
    std::filesystem::remove(from, ec);
    sysFail("cannot rename into place", to);
  }
  fsyncDirectory(to);
}

FileLock::FileLock(const std::filesystem::path& path) {
  const std::filesystem::path lock = resolveLinks(path).string() + ".lock";
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
