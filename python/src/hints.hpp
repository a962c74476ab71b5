#pragma once
/// @file hints.hpp
/// @brief Argument types that accept any Python object and only name, in
/// the signatures pybind11 writes into the docstrings (what help() and
/// editors without the .pyi show), the type python/lamina/*.pyi declares.
///
/// The bindings check their arguments themselves (lamina.InputError naming
/// the argument, never pybind11's TypeError listing overloads), so they take
/// plain objects; without these types every such argument would read
/// "handle" in help(). Hint<Tag> is a py::object whose check accepts
/// everything; handle_type_name<Hint<Tag>> gives Tag::name.

#include <pybind11/pybind11.h>

namespace lamina::python {

/// @return true: a Hint accepts every object (the binding checks it)
inline bool acceptAnyObject(PyObject* /*o*/) {
  return true;
}

/// A Python object whose signature name is @p Tag::name (see the file comment).
template <typename Tag>
class Hint : public pybind11::object {
public:
  PYBIND11_OBJECT_DEFAULT(Hint, pybind11::object, acceptAnyObject)
};

/// Declares the tag Alias##Tag and the argument type Alias = Hint<Alias##Tag>.
#define LAMINA_PY_HINT(Alias, text)                                                                \
  struct Alias##Tag {                                                                              \
    static constexpr auto name = pybind11::detail::const_name(text);                               \
  };                                                                                               \
  using Alias = Hint<Alias##Tag>

namespace hint {
LAMINA_PY_HINT(Path, "str | os.PathLike");                         ///< a file name
LAMINA_PY_HINT(OptionalPath, "str | os.PathLike | None");          ///< a file name or the default
LAMINA_PY_HINT(Case, "str | os.PathLike | Mapping[str, object]");  ///< a case file or its keys
LAMINA_PY_HINT(Overrides, "Mapping[str, object] | None");          ///< set={"key.path": value}
LAMINA_PY_HINT(Labels, "numpy.typing.ArrayLike");                  ///< a 3D integer array
LAMINA_PY_HINT(Phases, "Mapping[int, Mapping[str, object]]");      ///< phase id -> law keys
LAMINA_PY_HINT(Size, "float | tuple[float, float, float] | None"); ///< cell edge lengths (m)
LAMINA_PY_HINT(CellArg, "Cell");                                   ///< a lamina.Cell
LAMINA_PY_HINT(ResultArg, "HomogenizeResult");                     ///< a lamina.homogenize result
LAMINA_PY_HINT(Float, "float");                                    ///< a real number
LAMINA_PY_HINT(OptionalFloat, "float | None");                     ///< a real number or the default
LAMINA_PY_HINT(Int, "int");                                        ///< an integer
LAMINA_PY_HINT(OptionalInt, "int | None");                         ///< an integer or the default
LAMINA_PY_HINT(Bool, "bool");                                      ///< a flag
LAMINA_PY_HINT(Str, "str");                                        ///< a name
LAMINA_PY_HINT(Material, "str | Mapping[str, object]");            ///< a law: a name or its keys
LAMINA_PY_HINT(Plies, "Sequence[tuple[str, float, float]]");       ///< (material, angle, thickness)
LAMINA_PY_HINT(Progress, "Callable[..., object] | None");          ///< a progress callback
} // namespace hint

} // namespace lamina::python

namespace pybind11::detail {
/// The signature name of a lamina::python::Hint: its tag's.
template <typename Tag>
struct handle_type_name<lamina::python::Hint<Tag>> {
  static constexpr auto name = Tag::name; ///< as in python/lamina/*.pyi
};
} // namespace pybind11::detail
