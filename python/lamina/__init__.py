"""lamina from Python: unit cells, FFT homogenization, the materials library,
material laws and membrane runs, over the same C++ libraries as the
programs ``micro``, ``homogenize``, ``materials`` and ``membrane``.

Units are SI (m, kg, s, Pa); 6x6 stiffnesses and 6-vectors are in lamina's
order xx, yy, zz, yz, xz, xy with engineering shear strains (docs/python.md).
Long calls release the GIL, take an optional ``progress(done, total, label)``
callback and stop on Ctrl-C with KeyboardInterrupt.
"""

from ._errors import DivergenceError, Error, InputError
from ._lamina import __version__
from ._lamina import (Cell, HomogenizeResult, Library, blast, drive, homogenize,
                      homogenize_path)
from . import membrane

__all__ = [
    "Cell", "DivergenceError", "Error", "HomogenizeResult", "InputError", "Library",
    "__version__", "blast", "drive", "homogenize", "homogenize_path", "membrane",
]
