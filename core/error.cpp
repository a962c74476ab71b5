#include "core/error.hpp"

namespace lamina {

namespace {
std::string format(const std::string& message, const ErrorContext& c) {
  std::string out;
  if (!c.file.empty()) {
    out += c.file;
    if (c.line > 0)
      out += ":" + std::to_string(c.line);
    out += ": ";
  }
  if (!c.key.empty())
    out += "'" + c.key + "': ";
  out += message;
  return out;
}
} // namespace

Error::Error(const std::string& message, ErrorContext context)
    : std::runtime_error(format(message, context)), message_(message),
      context_(std::move(context)) {}

} // namespace lamina
