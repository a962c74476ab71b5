"""The type stubs say what the module has: every public name of
lamina/__init__.pyi and lamina/membrane.pyi exists at run time, every name
the package exports has a stub, and each function's and method's parameter
names (from the runtime's signature, or the first line of a pybind11
docstring) are the stub's, in order. So an editor's completion cannot
promise an argument the module refuses."""

import ast
import inspect
import pathlib
import re

import lamina
import lamina.membrane
import pytest

PACKAGE = pathlib.Path(lamina.__file__).parent


def stub_tree(name):
    return ast.parse((PACKAGE / name).read_text())


def stub_params(node):
    args = node.args
    names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
    return [n for n in names if n not in ("self", "cls")]


def runtime_params(obj):
    """Parameter names of a Python or pybind11 callable."""
    try:
        sig = inspect.signature(obj)
        return [p for p in sig.parameters if p not in ("self", "cls")]
    except (TypeError, ValueError):
        pass
    doc = (obj.__doc__ or "").strip().splitlines()
    assert doc, f"{obj!r} has neither a signature nor a docstring"
    first = doc[0]
    m = re.match(r"^[\w.]+\((.*)\)\s*(->.*)?$", first)
    assert m, f"{obj!r}: first docstring line is not a signature: {first!r}"
    inner = m.group(1)
    names, depth, cur = [], 0, ""
    for ch in inner + ",":
        if ch in "[(" :
            depth += 1
        elif ch in "])":
            depth -= 1
        if ch == "," and depth == 0:
            if cur.strip():
                names.append(cur.strip().split(":")[0].split("=")[0].strip())
            cur = ""
        else:
            cur += ch
    return [n for n in names if n not in ("self", "cls", "*", "/")]


def public_defs(tree):
    """(name, node) of the stub's top-level functions and classes."""
    return [(n.name, n) for n in tree.body
            if isinstance(n, (ast.FunctionDef, ast.ClassDef)) and not n.name.startswith("_")]


@pytest.mark.parametrize("stub,module", [("__init__.pyi", lamina),
                                         ("membrane.pyi", lamina.membrane)])
def test_every_stub_name_exists_with_the_stubs_parameters(stub, module):
    for name, node in public_defs(stub_tree(stub)):
        assert hasattr(module, name), f"{stub}: {name} is not in {module.__name__}"
        obj = getattr(module, name)
        if isinstance(node, ast.FunctionDef):
            assert runtime_params(obj) == stub_params(node), name
            continue
        for member in node.body:
            if not isinstance(member, ast.FunctionDef) or (
                    member.name.startswith("_") and member.name != "__init__"):
                continue
            if any(isinstance(d, ast.Name) and d.id == "property" for d in member.decorator_list):
                assert hasattr(obj, member.name), f"{name}.{member.name}"
                continue
            if member.name == "__init__" and obj.__init__ is object.__init__:
                pytest.fail(f"{name} has no __init__ but its stub has one")
            assert hasattr(obj, member.name), f"{name}.{member.name}"
            assert runtime_params(getattr(obj, member.name)) == stub_params(member), \
                f"{name}.{member.name}"


def test_every_exported_name_has_a_stub():
    stubbed = {name for name, _ in public_defs(stub_tree("__init__.pyi"))}
    tree = stub_tree("__init__.pyi")
    for node in tree.body:  # re-exports and module attributes
        if isinstance(node, ast.ImportFrom):
            stubbed |= {a.asname or a.name for a in node.names}
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            stubbed.add(node.target.id)
    missing = set(lamina.__all__) - stubbed
    assert not missing, f"exported without a stub: {sorted(missing)}"


def test_every_public_callable_has_a_docstring():
    for name in lamina.__all__:
        obj = getattr(lamina, name)
        if callable(obj):
            assert (obj.__doc__ or "").strip(), f"lamina.{name} has no docstring"


def pybind_callables():
    """(qualified name, callable) of every public function and method that
    the compiled extension defines (a pybind11 docstring signature)."""
    from lamina import _lamina
    out = []
    for name in dir(_lamina):
        obj = getattr(_lamina, name)
        if name.startswith("__"):
            continue
        if inspect.isclass(obj):
            for member in dir(obj):
                if member.startswith("__") and member not in ("__init__", "__getitem__",
                                                              "__contains__"):
                    continue
                fn = getattr(obj, member)
                if callable(fn) and (getattr(fn, "__doc__", None) or "").startswith(member + "("):
                    out.append((f"{name}.{member}", fn))
        elif callable(obj) and (obj.__doc__ or "").startswith(name + "("):
            out.append((name, obj))
    return out


def test_no_signature_names_a_pybind11_internal_type():
    # help() and editors without the stubs read the docstring's first line:
    # each argument names its Python type (python/src/hints.hpp), never
    # pybind11's "handle"
    found = pybind_callables()
    assert len(found) >= 15, [n for n, _ in found]  # the module's functions and methods
    for name, fn in found:
        first = fn.__doc__.splitlines()[0]
        assert not re.search(r":\s*handle\b", first), f"{name}: {first}"
