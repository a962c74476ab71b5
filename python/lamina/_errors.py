"""The exceptions lamina raises.

Every error of lamina's C++ libraries reaches Python as one of these, with
the context the programs print: ``str(e)`` is the programs' line
(``FILE:LINE: key 'KEY': MESSAGE``), and ``e.file``, ``e.line`` and ``e.key``
hold its parts (``None`` when unknown).
"""

from typing import Optional

__all__ = ["Error", "InputError", "DivergenceError"]


class Error(Exception):
    """Any failure lamina reports.

    Attributes:
        message: what went wrong, without the file, line and key.
        file: the input file it is about, or None.
        line: the 1-based line in that file, or None.
        key: the key, name or item it is about (a dotted TOML key, a
            material name, an element number, an argument name), or None.
    """

    def __init__(self, what: str, message: Optional[str] = None, file: Optional[str] = None,
                 line: Optional[int] = None, key: Optional[str] = None) -> None:
        super().__init__(what)
        self.message = what if message is None else message
        self.file = file
        self.line = line
        self.key = key


class InputError(Error, ValueError):
    """Bad input: a malformed file or dict, an unknown name, a value out of
    range, a wrong array. Also a ValueError."""


class DivergenceError(Error, ArithmeticError):
    """A run or a solve diverged (a non-finite state). The outputs written up
    to the last finite state are kept and closed; the message says when and
    where."""
