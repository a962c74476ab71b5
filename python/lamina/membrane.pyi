import os
from typing import Callable, Dict, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

class Result:
    """A membrane run's outputs, read back as arrays."""
    summary: Dict[str, object]  # summary.json
    probes: Dict[str, npt.NDArray[np.float64]]  # probes.csv: column -> array
    energy: Dict[str, npt.NDArray[np.float64]]  # energy.csv
    reactions: Dict[str, npt.NDArray[np.float64]]  # reactions.csv (empty without constraints)
    # fields at the asked times: for each, the written step NEAREST to it,
    # keyed by the time actually written -> field name -> array
    fields: Dict[float, Dict[str, npt.NDArray[np.float64]]]
    # compare_without_drag: {"with-drag": Result, "without-drag": Result}
    # (the case's probes/energy/reactions/fields are the run with drag); else {}
    runs: Dict[str, "Result"]
    out: Optional[str]  # the output folder (None: a temporary one, removed)

def run(case: Union[str, "os.PathLike[str]", Mapping[str, object]],
        set: Optional[Mapping[str, object]] = None,
        out: Optional[Union[str, "os.PathLike[str]"]] = None,
        fields: Optional[Sequence[float]] = None, threads: Optional[int] = None,
        progress: Optional[Callable[[int, int, str], object]] = None) -> Result:
    """`membrane run`: a case file's path, or a dict with the case file's
    keys (relative paths in it are relative to the working folder). `set`:
    {"time.dt": 5e-6, ...} as --set. Interrupted (Ctrl-C): the outputs are
    closed, summary.json says interrupted, KeyboardInterrupt is raised.
    out=None: a temporary folder, read back and removed. fields: times (s);
    Result.fields holds the field step written nearest to each."""
