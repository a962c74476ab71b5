#pragma once
/// @file common.hpp
/// @brief What every binding of the Python module shares: the translation
/// of lamina's errors into lamina.Error and its subclasses, and LongCall,
/// the frame of a long computation (GIL released, Ctrl-C through the
/// programs' interrupt handling, progress to an optional Python callback).
///
/// Errors (python/lamina/_errors.py defines the classes):
/// - lamina::DivergenceError -> lamina.DivergenceError (lamina.Error, ArithmeticError)
/// - lamina::Interrupted     -> KeyboardInterrupt (outputs already closed)
/// - lamina::Error           -> lamina.InputError (lamina.Error, ValueError): bad input
/// - other std::exception    -> lamina.Error
/// Each carries .message, .file, .line (None if unknown) and .key of the
/// lamina::ErrorContext; str() is the line the programs print.

#include "core/error.hpp"
#include "python/src/hints.hpp"

#include <pybind11/pybind11.h>

#include <exception>
#include <functional>
#include <optional>
#include <string>

namespace lamina::python {

namespace py = pybind11;

/// Registers the translator of C++ exceptions (above) on @p m; the classes
/// are looked up in lamina._errors when an error is raised.
void registerErrors(py::module_& m);

/// Raises lamina.InputError now (a check done in the binding itself: a
/// wrong dtype, an unknown dict key). @p key names what is wrong.
[[noreturn]] void throwInput(const std::string& message, const std::string& key = {});

/// The frame of a long call. Construct it with the GIL held, then call
/// run(): the GIL is released while @p work runs; on the main thread the
/// programs' InterruptGuard is installed, so that Ctrl-C stops the work at
/// its next safe point (a membrane run writes and closes its outputs, its
/// summary says interrupted) and run() raises KeyboardInterrupt; a second
/// Ctrl-C ends the process, as for the programs. @p progress (None: no
/// callback) is called as progress(done, total, label) from the calling
/// thread with the GIL held, at most every 0.2 s of each progress line; if
/// it raises, the work is asked to stop at its next safe point and run()
/// raises that exception.
class LongCall {
public:
  /// @param progress a callable or None
  explicit LongCall(py::object progress = py::none());
  /// Runs @p work as described; rethrows its exceptions (translated by
  /// registerErrors' translator when they reach Python).
  void run(const std::function<void()>& work);

private:
  py::object progress_;
};

/// @return @p o as a double, raising lamina.InputError naming @p key when it
/// is not a real number or (with @p finite) not finite
double toDouble(py::handle o, const std::string& key, bool finite = true);

/// Binders, one per source file (module.cpp calls them in this order).
/// @return the int @p o (not a bool), raising lamina.InputError naming @p key
/// otherwise or when it does not fit a long long
long long toInt(py::handle o, const std::string& key);

/// @return the type name of @p o (for messages: "got float")
std::string typeName(py::handle o);

/// @return @p path (a str or an os.PathLike) as a file name; None gives ""
/// (the caller's default). Raises lamina.InputError naming @p key for
/// another type or an empty path.
std::string pathArgument(py::handle path, const std::string& key);

/// @return @p path as pathArgument() does, but None is refused too: a
/// path the call needs (lamina.InputError naming @p key)
std::string requiredPath(py::handle path, const std::string& key);

/// @return @p name as a str; raises lamina.InputError naming @p key when it
/// is not a str
std::string strArgument(py::handle name, const std::string& key);

void bindCell(py::module_& m);       ///< cell.cpp: lamina.Cell
void bindHomogenize(py::module_& m); ///< homogenize.cpp: homogenize, homogenize_path
void bindLibrary(py::module_& m);    ///< library.cpp: lamina.Library
void bindLaws(py::module_& m);       ///< laws.cpp: drive
void bindMembrane(py::module_& m);   ///< membrane.cpp: membrane.run, blast
/// package.cpp: _default_catalog() (python/lamina/__init__.py falls back to the
/// catalog shipped in an installed package when that path does not exist)
void bindPackage(py::module_& m);

} // namespace lamina::python
