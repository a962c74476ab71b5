# Type stubs of the package lamina: the contract of the Python module.
# Units SI; 6x6 and 6-vectors in lamina's order xx, yy, zz, xy, yz, xz
# (engineering shear strains). Long calls (homogenize, homogenize_path,
# drive, membrane.run) release the GIL, take progress(done, total, label)
# and stop on Ctrl-C with KeyboardInterrupt.
import os
from typing import Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import membrane as membrane
from ._errors import DivergenceError as DivergenceError
from ._errors import Error as Error
from ._errors import InputError as InputError

__version__: str

PathLike = Union[str, "os.PathLike[str]"]
Progress = Optional[Callable[[int, int, str], object]]

class Cell:
    """A periodic voxel unit cell with its phases' laws."""

    @staticmethod
    def from_file(path: PathLike, set: Optional[Mapping[str, object]] = None,
                  catalog: Optional[PathLike] = None) -> "Cell":
        """Reads any cell file (generated inclusions, image cells) and builds
        its voxels, as `micro` and `homogenize` do. `set` holds
        {"cell.resolution": 16, ...}: the programs' --set KEY=VALUE."""
    @staticmethod
    def from_array(labels: npt.ArrayLike, phases: Mapping[int, Mapping[str, object]],
                   size: Union[None, float, Sequence[float]] = None,
                   catalog: Optional[PathLike] = None) -> "Cell":
        """A cell from a 3D integer array of phase ids, axis 0 = x, axis 1 =
        y, axis 2 = z (any integer dtype, C or Fortran order), and a dict
        phase id -> the keys of a cell file's [[phases]] table (name, law or
        catalog, E, nu, density...). `size`: edge lengths in metres (None:
        a scale-free cell of edge 1, no dispersion). The array is used
        without a copy when it is int32, C-contiguous and its ids are
        0..P-1 in the dict; otherwise it is copied (Cell.copied says which)."""
    def phase_map(self) -> npt.NDArray[np.int32]:
        """The phase index per voxel, shape resolution, axis 0 = x; a
        read-only view of the cell's own array (no copy)."""
    @property
    def resolution(self) -> Tuple[int, int, int]: ...
    @property
    def size(self) -> Tuple[float, float, float]: ...
    @property
    def phase_names(self) -> List[str]: ...
    @property
    def phase_fractions(self) -> Dict[str, float]:
        """Voxel fraction of each phase (cut voxels split by their fractions)."""
    @property
    def copied(self) -> bool:
        """from_array: whether the label array was copied."""
    @property
    def source(self) -> str:
        """The cell file's path, or "<array>"."""

class HomogenizeResult:
    """What lamina.homogenize returns (the `homogenize --json` fields)."""
    C: npt.NDArray[np.float64]  # 6x6, Pa
    density: float  # kg/m^3
    dispersion: Optional[npt.NDArray[np.float64]]  # 6x6 kg/m; None for a cell without size
    iterations: List[int]  # CG iterations of each of the six load cases
    residual: float
    symmetry: str
    phase_fractions: Dict[str, float]
    provenance: Dict[str, object]  # what a library entry records
    wall_s: float

def homogenize(cell: Cell, tol: Optional[float] = None, threads: Optional[int] = None,
               J: float = 1.0, progress: Progress = None) -> HomogenizeResult:
    """Effective stiffness, density and (cells with a size) dispersion
    tensor; the same solve as `homogenize CELL` (its defaults)."""

def homogenize_path(cell: Cell, path: str = "uniaxial-strain", rate: float = 1e4,
                    to: float = 0.1, steps: int = 100, unload: bool = False,
                    threads: Optional[int] = None,
                    progress: Progress = None) -> Dict[str, npt.NDArray[np.float64]]:
    """The nonlinear cell along a strain path (`homogenize CELL --path`):
    column -> array, the columns of its CSV (t, eps_xx..eps_xy,
    sig_xx..sig_xy, newton, krylov, residual, wall_s)."""

def drive(material: Union[str, Mapping[str, object]], path: str = "uniaxial-strain",
          rate: float = 1.0, to: float = 0.1, steps: int = 200, unload: bool = False,
          kinematics: str = "finite", library: Optional[PathLike] = None,
          catalog: Optional[PathLike] = None,
          progress: Progress = None) -> Dict[str, npt.NDArray[np.float64]]:
    """A material law driven point by point (`materials drive`): column ->
    array, the columns of its CSV. `material`: a library or catalog name,
    or a dict with the keys of a law (law = "gvbo", ...)."""

class Library(Mapping[str, Dict[str, object]]):
    """The materials library file: a mapping name -> entry (the fields of
    `materials show --json`, C as a 6x6 array). Writes are atomic and
    locked, as the programs'."""
    def __init__(self, path: Optional[PathLike] = None,
                 catalog: Optional[PathLike] = None) -> None:
        """path None: --library's default ($LAMINA_LIBRARY, then the XDG path)."""
    @property
    def path(self) -> str: ...
    def __getitem__(self, name: str) -> Dict[str, object]: ...
    def __contains__(self, name: object) -> bool: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def add(self, name: str, result: HomogenizeResult, overwrite: bool = False) -> None:
        """Adds a homogenized entry with its provenance (as `homogenize --name`)."""
    def add_from_catalog(self, name: str, catalog_name: str, overwrite: bool = False) -> None: ...
    def layup(self, name: str, plies: Sequence[Tuple[str, float, float]],
              overwrite: bool = False) -> None:
        """plies: (material, angle in degrees, thickness in m), bottom first."""
    def export(self, name: str, format: str = "json") -> str:
        """The text `materials export NAME --format FORMAT` prints."""
    def remove(self, name: str) -> None: ...

def blast(charge: float, distance: float, burst: str = "hemispherical") -> Dict[str, float]:
    """Kingery-Bulmash parameters (`membrane blast --json`): charge in kg TNT,
    distance in m."""
