"""Membrane runs from Python: ``lamina.membrane.run`` (the ``membrane run``
program's work, over the same library)."""

from ._lamina import _membrane_run as _run  # noqa: F401  (the C++ entry point)

__all__ = ["run"]


def run(case, set=None, out=None, fields=None, threads=None, progress=None):  # noqa: A002
    """See lamina/membrane.pyi."""
    raise NotImplementedError("lamina.membrane.run: being built")
