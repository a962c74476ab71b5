"""Membrane runs from Python: ``lamina.membrane.run`` (the ``membrane run``
program's work, over the same library) and its outputs read back as arrays."""

import json
import math
import numbers
import os
import pathlib
import re
import tempfile

import numpy as np

from ._errors import InputError
from ._lamina import _membrane_run, _read_h5

__all__ = ["Result", "run"]

# the folders of a compare_without_drag case's two runs (membrane/run.hpp)
_COMPARE_RUNS = ("with-drag", "without-drag")


def _read_csv(path):
    """CSV table with a header line -> {column: float64 array} (every value
    parsed from its shortest round-trip text: bit for bit the run's double)."""
    if not path.exists():
        return {}
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip()
        rows = [line.strip().split(",") for line in f if line.strip()]
    names = header.split(",") if header else []
    if not rows:
        return {n: np.empty(0) for n in names}
    table = np.array([[float(v) for v in r] for r in rows], dtype=np.float64)
    return {n: np.ascontiguousarray(table[:, i]) for i, n in enumerate(names)}


_GRID = re.compile(r'<Grid Name="step\d+"[^>]*>(.*?)</Grid>', re.S)
_TIME = re.compile(r'<Time Value="([^"]+)"')
_ATTRIBUTE = re.compile(r'<Attribute Name="([^"]+)".*?<DataItem[^>]*>[^<]*?:([^<:]+)</DataItem>',
                        re.S)


def _field_index(folder):
    """(h5 path, [(time, {field name: dataset})]) of the run's field series,
    from its .xdmf index (which lists the completed steps only); None when
    the run wrote no fields."""
    xdmfs = sorted(folder.glob("*.xdmf"))
    if not xdmfs:
        return None
    xdmf = xdmfs[0]
    steps = []
    for grid in _GRID.findall(xdmf.read_text(encoding="utf-8")):
        time = float(_TIME.search(grid).group(1))
        steps.append((time, dict(_ATTRIBUTE.findall(grid))))
    return xdmf.with_suffix(".h5"), steps


def _read_fields(folder, times):
    """{written time: {field: array}} at the written step nearest to each of
    @p times (ties: the earlier step)."""
    index = _field_index(folder)
    if index is None or not index[1]:
        raise InputError(f"fields asked for, but the run wrote no field steps in {folder} "
                         "(output.field_every)", key="fields")
    h5, steps = index
    written = np.array([t for t, _ in steps])
    out = {}
    for t in times:
        k = int(np.argmin(np.abs(written - t)))
        time, datasets = steps[k]
        if time not in out:
            out[time] = {name: _read_h5(str(h5), path) for name, path in datasets.items()}
    return out


class Result:
    """A membrane run's outputs, read back as arrays.

    Attributes:
        summary: summary.json as a dict (for a compare_without_drag case the
            case's summary: the run with drag plus "drag_comparison").
        probes, energy, reactions: probes.csv, energy.csv, reactions.csv as
            {column: float64 array} (the values the run wrote, bit for bit;
            reactions is empty without constraints).
        fields: for each time asked in run(fields=...), the field file's
            arrays at the written step NEAREST to it: {written time: {name:
            array}} (displacement and velocity (nodes x 3), speed, the
            element fields; geometry with a deformed mesh). Empty if none asked.
        runs: for a compare_without_drag case, {"with-drag": Result,
            "without-drag": Result}, each run's own outputs; else empty.
            The case's probes/energy/reactions/fields are those with drag.
        out: the output folder, or None when it was a temporary one (removed).
    """

    def __init__(self, summary, probes, energy, reactions, fields, runs, out):
        self.summary = summary
        self.probes = probes
        self.energy = energy
        self.reactions = reactions
        self.fields = fields
        self.runs = runs
        self.out = out

    def __repr__(self):
        return f"<lamina.membrane.Result: {self.summary.get('steps')} steps, out={self.out!r}>"


def _read_run(folder, times, out):
    """The Result of the run whose outputs are in @p folder."""
    summary_path = folder / "summary.json"
    summary = json.loads(summary_path.read_text(encoding="utf-8")) if summary_path.exists() else {}
    fields = _read_fields(folder, times) if times else {}
    return Result(summary, _read_csv(folder / "probes.csv"), _read_csv(folder / "energy.csv"),
                  _read_csv(folder / "reactions.csv"), fields, {}, out)


def _read_result(folder, times, out):
    """The Result of a case (one run, or a compare_without_drag case's two)."""
    runs = {name: _read_run(folder / name, times, None if out is None else str(folder / name))
            for name in _COMPARE_RUNS if (folder / name / "summary.json").exists()}
    if not runs:
        return _read_run(folder, times, out)
    summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    first = runs[_COMPARE_RUNS[0]] if _COMPARE_RUNS[0] in runs else next(iter(runs.values()))
    return Result(summary, first.probes, first.energy, first.reactions, first.fields, runs, out)


def _check_times(fields):
    """@p fields as a list of finite floats (lamina.InputError otherwise)."""
    if fields is None:
        return []
    if isinstance(fields, (str, bytes)) or not hasattr(fields, "__iter__"):
        raise InputError(f"fields must be a sequence of times in s, got {type(fields).__name__}",
                         key="fields")
    times = []
    for i, t in enumerate(fields):
        if isinstance(t, bool) or not isinstance(t, numbers.Real) or not math.isfinite(t):
            raise InputError(f"fields[{i}] must be a finite time in s, got {t!r}",
                             key=f"fields[{i}]")
        times.append(float(t))
    return times


def run(case, set=None, out=None, fields=None, threads=None, progress=None):  # noqa: A002
    """`membrane run`: a case file's path, or a dict with the case file's
    keys (relative paths in it are relative to the working folder). `set`:
    {"time.dt": 5e-6, ...} as --set. Interrupted (Ctrl-C): the outputs are
    closed, summary.json says interrupted, KeyboardInterrupt is raised.

    The computation is the program's (`membrane run CASE --out OUT --quiet`):
    the same outputs, bit for bit. A dict case's errors name "<dict>" as the
    file and the dotted key; without "name" its case name is "case".
    out: the output folder (created, kept); None: a temporary folder, read
    back and removed. fields: times (s); Result.fields holds, for each, the
    field step written NEAREST to it (output.field_every sets which are
    written), keyed by the time written. threads: OpenMP threads for this
    call (None: unchanged; restored after). progress(done, total, label):
    called at most every 0.2 s; if it raises, the run stops at its next step
    (outputs closed, summary says interrupted) and the exception propagates;
    with out=None the interrupted run's folder is removed with it.
    Returns a Result (probes, energy, reactions as {column: array})."""
    times = _check_times(fields)
    if out is not None:
        folder = pathlib.Path(os.fspath(out))
        _membrane_run(case, set, str(folder), threads, progress)
        return _read_result(folder, times, str(folder))
    with tempfile.TemporaryDirectory(prefix="lamina-membrane-") as tmp:
        folder = pathlib.Path(tmp)
        _membrane_run(case, set, str(folder), threads, progress)
        return _read_result(folder, times, None)

