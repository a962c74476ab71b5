#include "core/enum_names.hpp"

namespace lamina::core {

std::string choiceList(const std::vector<std::string_view>& names, char quote) {
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k > 0)
      out += k + 1 == names.size() ? " or " : ", ";
    out += quote;
    out += names[k];
    out += quote;
  }
  return out;
}

} // namespace lamina::core
