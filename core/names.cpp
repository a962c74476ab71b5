#include "core/names.hpp"

#include <cstdio>

namespace lamina::core {

namespace {
bool alnum(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

/// @return @p c printed for a message: itself, or its code when invisible
std::string shown(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u > 0x20 && u < 0x7f)
    return std::string("'") + c + "'";
  char buf[16];
  std::snprintf(buf, sizeof buf, "byte 0x%02x", u);
  return buf;
}
} // namespace

std::string nameProblem(std::string_view name) {
  if (name.empty())
    return "is empty";
  if (name.size() > kMaxNameLength)
    return "is longer than " + std::to_string(kMaxNameLength) + " characters";
  if (!alnum(name[0]))
    return "must start with a letter or a digit, not " + shown(name[0]);
  for (char c : name)
    if (!alnum(c) && c != '.' && c != '_' && c != '+' && c != '-')
      return "holds " + shown(c) + " (allowed: letters, digits, . _ + -)";
  return "";
}

bool isValidName(std::string_view name) {
  return nameProblem(name).empty();
}

void checkName(const std::string& name, const std::string& what, const ErrorContext& context) {
  const std::string why = nameProblem(name);
  if (why.empty())
    return;
  std::string printable;
  for (char c : name.substr(0, 60))
    printable += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
  throw Error(what + " '" + printable + (name.size() > 60 ? "..." : "") + "' " + why, context);
}

} // namespace lamina::core
