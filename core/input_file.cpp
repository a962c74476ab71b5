#include "core/input_file.hpp"

#include "core/resources.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lamina::core {

const char* fileKindName(mode_t mode) {
  if (S_ISFIFO(mode))
    return "a FIFO (named pipe)";
  if (S_ISCHR(mode))
    return "a character device";
  if (S_ISBLK(mode))
    return "a block device";
  if (S_ISDIR(mode))
    return "a directory";
  if (S_ISSOCK(mode))
    return "a socket";
  return "not a regular file";
}

InputFile::InputFile(const std::filesystem::path& path, const std::string& what,
                     std::uintmax_t max_bytes, ErrorContext where)
    : path_(path), what_(what), max_bytes_(max_bytes), where_(std::move(where)) {
  if (where_.file.empty())
    where_.file = path_.string();
  struct stat st {};
  if (::stat(path_.c_str(), &st) != 0)
    fail(std::string("cannot be opened: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    fail(std::string("is ") + fileKindName(st.st_mode) + ", not a regular file; refusing to read it");
  do
    fd_ = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  while (fd_ < 0 && errno == EINTR);
  if (fd_ < 0)
    fail(std::string("cannot be opened: ") + std::strerror(errno));
  // the file opened may not be the one stat()ed: check what is open
  if (::fstat(fd_, &st) != 0)
    fail(std::string("cannot be read: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    fail(std::string("is ") + fileKindName(st.st_mode) + ", not a regular file; refusing to read it");
  size_ = static_cast<std::uintmax_t>(st.st_size);
  if (size_ > max_bytes_)
    fail("of " + std::to_string(size_) + " bytes exceeds the limit of " +
         std::to_string(max_bytes_) + " bytes for a " + what_ + "; refusing to read it");
}

InputFile::~InputFile() {
  if (fd_ >= 0)
    ::close(fd_);
}

std::string InputFile::subject() const {
  return "the " + what_ + (where_.file == path_.string() ? "" : " " + path_.string());
}

void InputFile::fail(const std::string& message) const {
  if (fd_ >= 0)
    ::close(fd_);
  throw Error(subject() + " " + message, where_);
}

std::string InputFile::readAll() {
  requireMemory(static_cast<double>(size_), "reading the " + what_ + " " + path_.string(), where_);
  std::string out;
  out.reserve(static_cast<std::size_t>(size_));
  char buf[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0)
      throw Error(subject() + " cannot be read: " + std::strerror(errno), where_);
    if (n == 0)
      return out;
    if (out.size() + static_cast<std::size_t>(n) > max_bytes_)
      throw Error(subject() + " grew beyond the limit of " + std::to_string(max_bytes_) +
                      " bytes while it was read; refusing it",
                  where_);
    out.append(buf, static_cast<std::size_t>(n));
  }
}

void InputFile::readAt(std::uint64_t offset, void* data, std::size_t bytes) const {
  auto* to = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pread(fd_, to, bytes, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0)
      throw Error(subject() + " cannot be read: " + std::strerror(errno), where_);
    if (n == 0)
      throw Error(subject() + " ends at byte " + std::to_string(offset) +
                      ", before the data its header describes (truncated while read?)",
                  where_);
    to += n;
    offset += static_cast<std::uint64_t>(n);
    bytes -= static_cast<std::size_t>(n);
  }
}

std::uintmax_t checkRegularInput(const std::filesystem::path& path, const std::string& what,
                                 std::uintmax_t max_bytes, ErrorContext where) {
  return InputFile(path, what, max_bytes, std::move(where)).size();
}

std::string readWholeFile(const std::filesystem::path& path, std::uintmax_t max_bytes,
                          const std::string& what, ErrorContext where) {
  return InputFile(path, what, max_bytes, std::move(where)).readAll();
}

} // namespace lamina::core
