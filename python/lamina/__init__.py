"""lamina from Python: unit cells, FFT homogenization, the materials library,
material laws and membrane runs, over the same C++ libraries as the
programs ``micro``, ``homogenize``, ``materials`` and ``membrane``.

Units are SI (m, kg, s, Pa); 6x6 stiffnesses and 6-vectors are in lamina's
order xx, yy, zz, xy, yz, xz with engineering shear strains (docs/python.md).
Long calls release the GIL, take an optional ``progress(done, total, label)``
callback and stop on Ctrl-C with KeyboardInterrupt.
"""

import os as _os

from ._errors import DivergenceError, Error, InputError
from ._lamina import __version__
from ._lamina import _default_catalog
from ._lamina import (Cell, HomogenizeResult, Library, blast, drive, homogenize,
                      homogenize_path)
from . import membrane


def _use_packaged_catalog():
    """An installed package (pip install .) ships the source tree's
    materials/catalog.toml as lamina/catalog.toml. It becomes this process's
    $LAMINA_CATALOG when that is unset and the compiled-in catalog (the path
    of the source tree the package was built from) does not exist."""
    packaged = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "catalog.toml")
    if (not _os.environ.get("LAMINA_CATALOG") and not _os.path.exists(_default_catalog())
            and _os.path.exists(packaged)):
        _os.environ["LAMINA_CATALOG"] = packaged


_use_packaged_catalog()

__all__ = [
    "Cell", "DivergenceError", "Error", "HomogenizeResult", "InputError", "Library",
    "__version__", "blast", "drive", "homogenize", "homogenize_path", "membrane",
]
