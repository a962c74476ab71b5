#include "python/src/common.hpp"

#include "core/interrupt.hpp"
#include "core/progress.hpp"

#include <cmath>
#include <csignal>
#include <new>
#include <optional>

namespace lamina::python {

namespace {

/// Raises the class @p name of lamina._errors for @p e (GIL held: inside a
/// translator).
void raiseLaminaError(const char* name, const std::string& what, const std::string& message,
                      const ErrorContext& context) {
  try {
    const py::object type = py::module_::import("lamina._errors").attr(name);
    const py::object instance = type(
        what, py::arg("message") = message,
        py::arg("file") = context.file.empty() ? py::object(py::none()) : py::str(context.file),
        py::arg("line") = context.line > 0 ? py::object(py::int_(context.line)) : py::none(),
        py::arg("key") = context.key.empty() ? py::object(py::none()) : py::str(context.key));
    PyErr_SetObject(type.ptr(), instance.ptr());
  } catch (py::error_already_set& e) { // lamina._errors missing: the module used alone
    e.restore();
  }
}

} // namespace

void registerErrors(py::module_& m) {
  (void)m;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p)
        std::rethrow_exception(p);
    } catch (const Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const DivergenceError& e) {
      raiseLaminaError("DivergenceError", e.what(), e.message(), e.context());
    } catch (const Error& e) {
      raiseLaminaError("InputError", e.what(), e.message(), e.context());
    } catch (const py::builtin_exception&) {
      throw; // pybind11's own (value_error, index_error...): its translator
    } catch (const py::error_already_set&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw; // MemoryError
    } catch (const std::exception& e) {
      raiseLaminaError("Error", e.what(), e.what(), {});
    }
  });
}

void throwInput(const std::string& message, const std::string& key) {
  throw Error(message, ErrorContext{"", 0, key});
}

double toDouble(py::handle o, const std::string& key, bool finite) {
  if (o.is_none() || py::isinstance<py::str>(o) || py::isinstance<py::bool_>(o) ||
      !PyNumber_Check(o.ptr()))
    throwInput("expected a number, got " + typeName(o), key);
  const double v = o.cast<double>();
  if (finite && !std::isfinite(v))
    throwInput("expected a finite number, got " + std::string(py::str(o)), key);
  return v;
}

LongCall::LongCall(py::object progress) : progress_(std::move(progress)) {
  if (!progress_.is_none() && !PyCallable_Check(progress_.ptr()))
    throwInput("progress must be a callable progress(done, total, label) or None", "progress");
}

void LongCall::run(const std::function<void()>& work) {
  const py::module_ threading = py::module_::import("threading");
  const bool main_thread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  std::optional<py::error_already_set> callback_error;
  core::ProgressObserver observer;
  if (!progress_.is_none())
    observer = [&](const std::string& label, long done, long total) {
      if (callback_error)
        return;
      py::gil_scoped_acquire gil;
      try {
        progress_(done, total, label);
      } catch (py::error_already_set& e) {
        callback_error.emplace(std::move(e));
        core::requestInterrupt(SIGINT); // stop at the next safe point
      }
    };
  std::optional<core::InterruptGuard> guard;
  if (main_thread)
    guard.emplace(); // SIGINT/SIGTERM now stop the work at a safe point
  std::exception_ptr error;
  {
    core::ScopedProgressObserver scope(observer);
    py::gil_scoped_release release;
    try {
      work();
    } catch (...) {
      error = std::current_exception();
    }
  }
  const int signal = core::interruptSignal();
  guard.reset(); // Python's handlers again
  core::requestInterrupt(0);
  if (callback_error)
    throw std::move(*callback_error);
  if (error)
    std::rethrow_exception(error);
  if (signal == SIGINT && main_thread)
    PyErr_SetInterrupt(); // Ctrl-C after the last safe point: KeyboardInterrupt next
}

long long toInt(py::handle o, const std::string& key) {
  if (py::isinstance<py::bool_>(o) || !PyIndex_Check(o.ptr()))
    throwInput("expected an integer, got " + typeName(o), key);
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(o.ptr()));
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0)
    throwInput("integer out of range: " + std::string(py::str(o)), key);
  return v;
}

std::string typeName(py::handle o) {
  return py::str(py::type::of(o).attr("__name__"));
}

std::string pathArgument(py::handle path, const std::string& key) {
  if (path.is_none())
    return {};
  if (!py::isinstance<py::str>(path) && !py::hasattr(path, "__fspath__"))
    throwInput("expected a path (str or os.PathLike) or None, got " + typeName(path), key);
  const py::module_ os = py::module_::import("os");
  const std::string text = os.attr("fsdecode")(os.attr("fspath")(path)).cast<std::string>();
  if (text.empty())
    throwInput("an empty path names no file (None: the default)", key);
  return text;
}

std::string requiredPath(py::handle path, const std::string& key) {
  if (path.is_none())
    throwInput("expected a path (str or os.PathLike), got None", key);
  return pathArgument(path, key);
}

std::string strArgument(py::handle name, const std::string& key) {
  if (!py::isinstance<py::str>(name))
    throwInput("expected a str, got " + typeName(name), key);
  return name.cast<std::string>();
}

} // namespace lamina::python
