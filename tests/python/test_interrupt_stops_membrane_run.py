"""A membrane run from Python stops as the program's does on Ctrl-C: at its
next step, with its outputs written and closed and summary.json saying it
was interrupted; (a) a progress callback that raises stops it and its
exception reaches the caller; (b) a real SIGINT (in a child interpreter)
raises KeyboardInterrupt there, after which the child goes on normally."""

import csv
import json
import os
import subprocess
import sys
import textwrap

import pytest

import lamina

# case1 on a finer grid: 60 steps of a 121 x 121 grid (long enough for a progress call)
SETS = {"mesh.nx": 121}
FULL_STEPS = 60


class Stop(Exception):
    """The callback's own exception (not a lamina error)."""


def rows(path):
    """The data rows of a CSV table (each a list of floats: all readable numbers)."""
    with open(path, newline="") as f:
        table = list(csv.reader(f))
    return [[float(v) for v in r] for r in table[1:]]


def test_progress_callback_that_raises_stops_the_run(source_dir, tmp_path):
    calls = []

    def progress(done, total, label):
        calls.append((done, total, label))
        raise Stop("enough")

    case = source_dir / "cases" / "membrane" / "case1.toml"
    with pytest.raises(Stop, match="enough"):
        lamina.membrane.run(case, set=SETS, out=tmp_path, progress=progress)
    assert len(calls) == 1  # not called again once it raised
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["interrupted"] is True
    assert summary["steps"] < FULL_STEPS
    probes = rows(tmp_path / "probes.csv")  # closed: renamed from .part, every row complete
    assert len(probes) == summary["steps"] + 1  # t = 0 and each step taken
    assert not (tmp_path / "probes.csv.part").exists()
    assert (tmp_path / "checkpoint.h5").exists()  # as the program: a restart can continue
    # the module works normally afterwards: no interrupt left pending
    r = lamina.membrane.run(case, set={"mesh.nx": 11, "time.t_end": 1e-4})
    assert r.summary["interrupted"] is False and r.summary["steps"] == 10


CHILD = textwrap.dedent("""
    import json, os, signal, sys
    import lamina
    sent = []
    def progress(done, total, label):
        if not sent:  # one Ctrl-C (a second one ends the process, as for the programs)
            sent.append(done)
            os.kill(os.getpid(), signal.SIGINT)
    try:
        lamina.membrane.run(sys.argv[1], set={"mesh.nx": 121}, out=sys.argv[2],
                            progress=progress)
    except KeyboardInterrupt as e:
        print("KeyboardInterrupt:", e)
    else:
        print("finished")
    # the interpreter goes on: a second run completes
    r = lamina.membrane.run(sys.argv[1], set={"mesh.nx": 11, "time.t_end": 1e-4})
    print("after:", r.summary["steps"], r.summary["interrupted"])
""")


def test_sigint_raises_keyboard_interrupt_after_closing_the_outputs(source_dir, tmp_path):
    case = source_dir / "cases" / "membrane" / "case1.toml"
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-c", CHILD, str(case), str(out)],
                          capture_output=True, text=True, timeout=120, env=os.environ.copy())
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith("KeyboardInterrupt: interrupted by SIGINT"), proc.stdout
    assert lines[1] == "after: 10 False"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["interrupted"] is True and summary["signal"] == "SIGINT"
    assert summary["steps"] < FULL_STEPS
    assert len(rows(out / "probes.csv")) == summary["steps"] + 1
    assert len(rows(out / "energy.csv")) >= 1
