"""lamina.membrane.run does what `membrane run` does: on the same case file
and --set options it writes the same probes.csv, energy.csv and
reactions.csv byte for byte, returns their values bit for bit, returns the
field file's arrays as written, and a dict with the case file's keys gives
the same arrays as the file; a compare_without_drag case returns both runs."""

import csv
import json
import pathlib
import tomllib

import h5py
import numpy as np
import pytest

import lamina

SETS = {"mesh.nx": 11, "time.t_end": 3.0e-4}  # case1, small: 30 steps
SET_ARGS = ["--set", "mesh.nx=11", "--set", "time.t_end=3.0e-4"]
TABLES = ("probes.csv", "energy.csv", "reactions.csv")


def program_table(path):
    """The program's CSV parsed here, column -> array (independently of the module)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


def assert_bitwise(a, b):
    assert a.keys() == b.keys()
    for name in a:
        assert a[name].dtype == np.float64
        # bit for bit: the same doubles (tobytes compares -0.0 and NaN payloads too)
        assert a[name].tobytes() == b[name].tobytes(), name


def without_timings(summary):
    """summary.json without its wall-clock entries (*_s: seconds measured, which differ)."""
    if isinstance(summary, dict):
        return {k: without_timings(v) for k, v in summary.items() if not k.endswith("_s")}
    return summary


@pytest.fixture
def program_run(program, source_dir, tmp_path):
    case = source_dir / "cases" / "membrane" / "case1.toml"
    out = tmp_path / "program"
    program("membrane", "run", case, "--out", out, "--quiet", *SET_ARGS)
    return case, out


def test_case_file_writes_the_programs_tables_and_returns_their_values(program_run, tmp_path):
    case, program_out = program_run
    out = tmp_path / "python"
    r = lamina.membrane.run(case, set=SETS, out=out)
    for name in TABLES:
        assert (out / name).read_bytes() == (program_out / name).read_bytes(), name
    assert_bitwise(r.probes, program_table(program_out / "probes.csv"))
    assert_bitwise(r.energy, program_table(program_out / "energy.csv"))
    assert_bitwise(r.reactions, program_table(program_out / "reactions.csv"))
    assert r.summary == json.loads((out / "summary.json").read_text())
    assert without_timings(r.summary) == \
        without_timings(json.loads((program_out / "summary.json").read_text()))
    assert r.summary["steps"] == 30 and r.summary["interrupted"] is False
    assert r.out == str(out)


def test_temporary_folder_is_removed_and_fields_are_the_written_steps(program_run, tmp_path,
                                                                       monkeypatch):
    case, program_out = program_run
    monkeypatch.setenv("TMPDIR", str(tmp_path))  # tempfile's folder, to see it removed
    import tempfile
    monkeypatch.setattr(tempfile, "tempdir", None)
    # field_every = 10 at dt = 1e-5: steps written at t = 0, 1e-4, 2e-4, 3e-4
    r = lamina.membrane.run(case, set=SETS, fields=[0.9e-4, 2.2e-4])
    assert r.out is None
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith("lamina-")] == []
    assert_bitwise(r.probes, program_table(program_out / "probes.csv"))
    with h5py.File(program_out / "case1.h5", "r") as h5:
        written = {float(h5[f"steps/{k}"].attrs["time"]): k for k in range(len(h5["steps"]))}
        assert len(written) == 4
        # the written step nearest to each asked time, keyed by its written time
        assert sorted(r.fields) == sorted(min(written, key=lambda w: abs(w - t))
                                          for t in (0.9e-4, 2.2e-4))
        for t, arrays in r.fields.items():
            group = h5[f"steps/{written[t]}"]
            assert set(arrays) == set(group.keys())
            for name, a in arrays.items():
                assert a.shape == group[name].shape
                assert a.tobytes() == np.asarray(group[name], dtype=np.float64).tobytes(), name


def test_dict_case_gives_the_arrays_of_its_file(program_run, source_dir, tmp_path, monkeypatch):
    case, program_out = program_run
    with open(case, "rb") as f:
        doc = tomllib.load(f)
    monkeypatch.chdir(tmp_path)  # relative paths of a dict resolve here (none in case1)
    r = lamina.membrane.run(doc, set=SETS)
    assert_bitwise(r.probes, program_table(program_out / "probes.csv"))
    assert_bitwise(r.energy, program_table(program_out / "energy.csv"))
    assert_bitwise(r.reactions, program_table(program_out / "reactions.csv"))


def test_dict_case_mesh_path_is_relative_to_the_working_folder(source_dir, tmp_path, program,
                                                               monkeypatch):
    """A gmsh mesh named relative to the working folder (not to a case file)."""
    case = source_dir / "cases" / "membrane" / "circle-impact.toml"
    with open(case, "rb") as f:
        doc = tomllib.load(f)
    assert doc["mesh"]["file"] == "../meshes/circle.geo"
    sets = {"time.t_end": 20 * doc["time"]["dt"]}
    program("membrane", "run", case, "--out", tmp_path / "program", "--quiet",
            "--set", f"time.t_end={sets['time.t_end']!r}")
    monkeypatch.chdir(case.parent)  # the case file's folder: its relative mesh path holds
    r = lamina.membrane.run(doc, set=sets)
    assert_bitwise(r.probes, program_table(tmp_path / "program" / "probes.csv"))
    monkeypatch.chdir(tmp_path)  # from elsewhere the same relative path names no file
    with pytest.raises(lamina.InputError, match="circle.geo"):
        lamina.membrane.run(doc, set=sets)


def test_compare_without_drag_case_returns_both_runs(program, source_dir, tmp_path):
    case = source_dir / "cases" / "membrane" / "impulsive-panel.toml"
    sets = {"mesh.nx": 8, "time.t_end": 0.02}
    program("membrane", "run", case, "--out", tmp_path / "program", "--quiet",
            "--set", "mesh.nx=8", "--set", "time.t_end=0.02")
    r = lamina.membrane.run(case, set=sets, out=tmp_path / "python")
    assert set(r.runs) == {"with-drag", "without-drag"}
    assert without_timings(r.summary) == \
        without_timings(json.loads((tmp_path / "program" / "summary.json").read_text()))
    assert "drag_comparison" in r.summary
    for name, run in r.runs.items():
        folder = tmp_path / "program" / name
        assert without_timings(run.summary) == \
            without_timings(json.loads((folder / "summary.json").read_text()))
        assert_bitwise(run.probes, program_table(folder / "probes.csv"))
        assert_bitwise(run.reactions, program_table(folder / "reactions.csv"))
    # drag slows the panel: the two runs differ (the comparison is not of one run with itself)
    assert r.runs["with-drag"].energy["kinetic"].tobytes() != \
        r.runs["without-drag"].energy["kinetic"].tobytes()
    assert r.probes is r.runs["with-drag"].probes


def test_threads_option_computes_as_the_programs_threads_option(program, source_dir, tmp_path):
    case = source_dir / "cases" / "membrane" / "case1.toml"
    program("membrane", "run", case, "--out", tmp_path / "program", "--quiet", "--threads", "2",
            *SET_ARGS)
    r = lamina.membrane.run(case, set=SETS, threads=2, out=tmp_path / "python")
    for name in TABLES:
        assert (tmp_path / "python" / name).read_bytes() == \
            (tmp_path / "program" / name).read_bytes(), name
    assert r.summary["steps"] == 30
