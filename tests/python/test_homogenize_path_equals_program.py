"""lamina.homogenize_path is the program's nonlinear run: on the GVBO
polyurea cell (8^3 voxels, a few steps, one thread in both) its columns are
those of the CSV `homogenize CELL --path P --out F.csv` writes, in the same
order, and every value but the wall times equals the CSV's bit for bit (the
CSV keeps 17 significant digits, so its text parses back to the same
doubles)."""

import csv

import lamina
import numpy as np
import pytest

RUNS = [dict(path="uniaxial-strain", rate=1e4, to=0.01, steps=3, unload=False),
        dict(path="shear", rate=1e3, to=0.02, steps=2, unload=True)]


@pytest.mark.parametrize("run", RUNS, ids=[r["path"] for r in RUNS])
def test_path_columns_equal_the_programs_csv(source_dir, library_path, program, tmp_path, run):
    cell_file = source_dir / "cases" / "cells" / "polyurea.toml"
    out = tmp_path / "history.csv"
    args = [cell_file, "--set", "cell.resolution=8", "--path", run["path"], "--rate", run["rate"],
            "--to", run["to"], "--steps", run["steps"], "--out", out, "--threads", 1, "--quiet"]
    if run["unload"]:
        args.append("--unload")
    program("homogenize", *args)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    header, values = rows[0], np.array(rows[1:], dtype=float)

    cell = lamina.Cell.from_file(cell_file, set={"cell.resolution": 8})
    columns = lamina.homogenize_path(cell, threads=1, **run)
    assert list(columns) == header
    steps = run["steps"] * (2 if run["unload"] else 1)
    assert values.shape[0] == steps + 1
    for i, name in enumerate(header):
        assert columns[name].dtype == np.float64
        assert columns[name].shape == (steps + 1,)
        if name != "wall_s":
            assert np.array_equal(columns[name], values[:, i]), name
    assert columns["sig_xx" if run["path"] != "shear" else "sig_xy"][1] != 0
