#pragma once
/// @file enum_names.hpp
/// @brief The names users type for the values of an enum (a law, a strain
/// path, an image format, a model kind): one table of {name, value} pairs
/// per enum, kept next to the enum, that parses, prints and lists them.
///
///     inline constexpr auto kShapeNames =
///         core::enumNames<Shape>({{"sphere", Shape::Sphere}, {"fiber", Shape::Fiber}});
///     kShapeNames.parse("fiber")   // Shape::Fiber (nothing for an unknown name)
///     kShapeNames.name(Shape::Fiber) // "fiber"
///     kShapeNames.list()           // "'sphere' or 'fiber'" (for messages)
///     kShapeNames.names()          // {"sphere", "fiber"} (CLI::IsMember)
///
/// A table is also a range of (name, value) pairs, so TableReader::getChoice
/// reads a key through it. A value may have more than one name (an alias):
/// name() gives the first.

#include "core/error.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lamina::core {

/// @return @p names, each between @p quote, joined for a message:
/// "'a'", "'a' or 'b'", "'a', 'b' or 'c'"
std::string choiceList(const std::vector<std::string_view>& names, char quote = '\'');

/// The names of the values of enum @p E: @p N (name, value) pairs, in the
/// order messages and --help list them.
template <class E, std::size_t N>
struct EnumNames {
  std::array<std::pair<std::string_view, E>, N> entries; ///< (name, value), names distinct

  /// @return the value named @p name (exact spelling), or nothing
  constexpr std::optional<E> parse(std::string_view name) const {
    for (const auto& [n, v] : entries)
      if (n == name)
        return v;
    return std::nullopt;
  }
  /// @return the (first) name of @p value; every value of E has one
  constexpr std::string_view name(E value) const {
    for (const auto& [n, v] : entries)
      if (v == value)
        return n;
    LAMINA_ASSERT(false && "an enum value without a name");
    return "?";
  }
  /// @return the names, in table order (for CLI::IsMember)
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries)
      out.emplace_back(e.first);
    return out;
  }
  /// @return the names quoted for a message: "'a', 'b' or 'c'"
  std::string list(char quote = '\'') const {
    std::vector<std::string_view> out;
    for (const auto& e : entries)
      out.push_back(e.first);
    return choiceList(out, quote);
  }
  /// @return the value named @p name; otherwise throws lamina::Error
  /// "unknown WHAT 'NAME' (expected 'a', 'b' or 'c')" with @p context
  E parseOrThrow(std::string_view name, std::string_view what, const ErrorContext& context) const {
    if (const std::optional<E> v = parse(name))
      return *v;
    throw Error("unknown " + std::string(what) + " '" + std::string(name) + "' (expected " +
                    list() + ")",
                context);
  }

  /// Iteration over the (name, value) pairs.
  constexpr auto begin() const { return entries.begin(); }
  /// End of the pairs.
  constexpr auto end() const { return entries.end(); }
  /// @return N
  static constexpr std::size_t size() { return N; }
};

namespace detail {
template <class E, std::size_t N, std::size_t... I>
constexpr EnumNames<E, N> enumNames(const std::pair<std::string_view, E> (&entries)[N],
                                    std::index_sequence<I...>) {
  return {{{entries[I]...}}};
}
} // namespace detail

/// @return the table of the (name, value) pairs @p entries (N counted for
/// the caller): `enumNames<E>({{"a", E::A}, {"b", E::B}})`
template <class E, std::size_t N>
constexpr EnumNames<E, N> enumNames(const std::pair<std::string_view, E> (&entries)[N]) {
  return detail::enumNames(entries, std::make_index_sequence<N>());
}

} // namespace lamina::core
