"""lamina.homogenize is the program's computation: on the same small case
cells (cases/cells at 8 to 16 voxels, generated and an image cell, one thread
in both) its C, density,
dispersion, iterations and residual equal, bit for bit, what
`homogenize CELL --set ... --name X --json` prints (the JSON keeps 17
significant digits, so its numbers parse back to the same doubles), and the
provenance of the result is that of the library entry the program writes
(cell text, --set, resolution, voxels, fractions, iterations, residuals)."""

import json
import tomllib

import lamina
import numpy as np
import pytest

CASES = [("sphere.toml", 8), ("fiber.toml", 8), ("laminate.toml", None),
         ("polyurea.toml", 8), ("plain-weave.toml", 16), ("particles-scan.toml", None)]


def settings(resolution):
    if resolution is None:
        return {}
    return {"cell.resolution": resolution}


def program_json(program, cell_file, resolution, name="x"):
    args = [cell_file, "--name", name, "--json", "--threads", 1]
    for key, value in settings(resolution).items():
        args += ["--set", f"{key}={value}"]
    out = program("homogenize", *args).stdout
    return json.loads(out.strip().splitlines()[-1])


@pytest.mark.parametrize("cell_name,resolution", CASES)
def test_homogenize_equals_the_programs_json(source_dir, library_path, program, cell_name,
                                             resolution):
    path = source_dir / "cases" / "cells" / cell_name
    expected = program_json(program, path, resolution)
    cell = lamina.Cell.from_file(path, set=settings(resolution) or None)
    r = lamina.homogenize(cell, threads=1)
    assert np.array_equal(r.C, np.array(expected["C"])), cell_name
    assert r.density == expected["density"]
    assert r.iterations == expected["iterations"]
    assert r.residual == expected["residual"]
    assert r.symmetry == expected["symmetry"]
    assert list(r.phase_fractions.values()) == expected["phase_fractions"]
    if "dispersion" in expected:
        assert np.array_equal(r.dispersion, np.array(expected["dispersion"]))
    else:
        assert r.dispersion is None


def test_provenance_is_the_programs_library_entry(source_dir, library_path, program):
    path = source_dir / "cases" / "cells" / "sphere.toml"
    program_json(program, path, 8, name="from-program")
    written = tomllib.loads(library_path.read_text())["materials"]["from-program"]["provenance"]
    r = lamina.homogenize(lamina.Cell.from_file(path, set={"cell.resolution": 8}), threads=1)
    p = r.provenance
    for key in ("cell_file", "cell_text", "cell_overrides", "resolution", "voxels",
                "volume_fractions", "phases", "composite_voxels", "J", "solver", "tol",
                "iterations", "residuals", "residual", "symmetry", "dispersion_residuals"):
        assert p[key] == written[key], key
    assert p["program"] != written["program"]  # says it came from the module


@pytest.mark.skipif(lamina.Library is None, reason="lamina.Library is bound by its own work")
def test_library_add_writes_the_programs_entry(source_dir, library_path, program):
    path = source_dir / "cases" / "cells" / "sphere.toml"
    program_json(program, path, 8, name="from-program")
    r = lamina.homogenize(lamina.Cell.from_file(path, set={"cell.resolution": 8}), threads=1)
    lib = lamina.Library(library_path)
    lib.add("from-module", r)
    lib = lamina.Library(library_path)
    a, b = lib["from-program"], lib["from-module"]
    assert np.array_equal(np.asarray(a["C"]), np.asarray(b["C"]))
    assert a["density"] == b["density"]
    assert np.array_equal(np.asarray(a["dispersion"]), np.asarray(b["dispersion"]))
    with pytest.raises(lamina.InputError, match="from-module"):
        lib.add("from-module", r)
