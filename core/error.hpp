#pragma once
/// @file error.hpp
/// @brief The one error type of lamina and the two checking macros.
///
/// User errors (bad input, unknown names, non-positive-definite stiffness) are
/// reported with LAMINA_CHECK, which is always on and throws lamina::Error.
/// Internal invariants use LAMINA_ASSERT, which is compiled only in debug
/// builds (NDEBUG unset) and aborts: a failed assert is a bug in lamina.

#include <cassert>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lamina {

/// Where an error comes from: a file, a line in it (0 = unknown) and a key
/// (dotted TOML path, material name, element id...). Any part may be empty.
struct ErrorContext {
  std::string file; ///< path of the input file, if any
  int line = 0;     ///< 1-based line in that file, 0 if unknown
  std::string key;  ///< key, name or item the error is about
};

/// Error raised for every user-facing failure. what() is one line:
/// "FILE:LINE: key 'KEY': MESSAGE" with the parts that are known.
class Error : public std::runtime_error {
public:
  /// @param message what went wrong, without context
  /// @param context where (file, line, key); may be empty
  explicit Error(const std::string& message, ErrorContext context = {});

  /// @return the bare message, without the context prefix
  const std::string& message() const { return message_; }
  /// @return the context given at construction
  const ErrorContext& context() const { return context_; }

private:
  std::string message_;
  ErrorContext context_;
};

/// Error raised when a time integration or an iterative solve diverges
/// (NaN/Inf). Programs map it to a distinct exit code (3).
class DivergenceError : public Error {
public:
  using Error::Error;
};

/// What a program's command-line function does with an exception that is
/// not a lamina::Error (a std::exception or anything else): Report it and
/// exit 1 (the programs), or Rethrow it (the argument fuzzer: a finding).
enum class UnexpectedErrors { Report, Rethrow };

/// Exit codes shared by all lamina programs.
enum ExitCode : int {
  kExitOk = 0,         ///< success
  kExitUserError = 1,  ///< bad input, unknown name, invalid material
  kExitUsage = 2,      ///< bad command line
  kExitDivergence = 3, ///< NaN/Inf during a run: last good state written
};

namespace detail {
/// Builds the message of a failed LAMINA_CHECK from a stream expression.
template <typename... Args>
std::string concat(const Args&... args) {
  std::ostringstream os;
  (os << ... << args);
  return os.str();
}
} // namespace detail

} // namespace lamina

/// Always-on check of a user-facing condition: throws lamina::Error with the
/// streamed message when @p cond is false.
#define LAMINA_CHECK(cond, ...)                                                                    \
  do {                                                                                             \
    if (!(cond))                                                                                   \
      throw ::lamina::Error(::lamina::detail::concat(__VA_ARGS__));                                \
  } while (0)

/// Debug-only assertion of an internal invariant.
#define LAMINA_ASSERT(cond) assert(cond)
