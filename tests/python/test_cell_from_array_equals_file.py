"""Cell.from_array of the phase map `micro CELL --out X.h5` writes (read
with h5py; its labels are the phase ids) and of the cell file's own
[[phases]] tables gives the cell Cell.from_file builds: the same phase map
and the same C, density and dispersion bit for bit (composite voxels off:
the array carries whole voxels only). In place (int32, C order, ids 0..P-1)
or copied (int64, Fortran order, ids shifted), the result is the same."""

import tomllib

import h5py
import lamina
import numpy as np
import pytest

SET = {"cell.resolution": 8, "cell.composite_voxels": False}


def phases_of(cell_file, shift=0):
    tables = tomllib.loads(cell_file.read_text())["phases"]
    return {i + shift: table for i, table in enumerate(tables)}


def micro_labels(program, cell_file, tmp_path):
    out = tmp_path / "phases.h5"
    program("micro", cell_file, "--out", out, *[a for k, v in SET.items()
                                                 for a in ("--set", f"{k}={str(v).lower()}")])
    with h5py.File(out, "r") as f:
        return f["/phases"][...]


@pytest.mark.parametrize("cell_name", ["sphere.toml", "polyurea.toml"])
def test_array_cell_is_the_file_cell(source_dir, program, tmp_path, cell_name):
    cell_file = source_dir / "cases" / "cells" / cell_name
    labels = micro_labels(program, cell_file, tmp_path)
    assert labels.dtype == np.int32 and labels.shape == (8, 8, 8)
    size = tomllib.loads(cell_file.read_text())["cell"]["size"]
    from_file = lamina.Cell.from_file(cell_file, set=SET)
    expected = lamina.homogenize(from_file, threads=1)

    in_place = lamina.Cell.from_array(labels, phases_of(cell_file), size=size)
    assert not in_place.copied
    copied = lamina.Cell.from_array(np.asfortranarray(labels.astype(np.int64) + 5),
                                    phases_of(cell_file, shift=5), size=[size] * 3)
    assert copied.copied
    for cell in (in_place, copied):
        assert np.array_equal(cell.phase_map(), from_file.phase_map())
        assert cell.phase_fractions == from_file.phase_fractions
        assert cell.size == from_file.size
        r = lamina.homogenize(cell, threads=1)
        assert np.array_equal(r.C, expected.C)
        assert r.density == expected.density
        assert np.array_equal(r.dispersion, expected.dispersion)
        assert r.iterations == expected.iterations


def test_array_cell_provenance_describes_the_array(source_dir, program, tmp_path):
    cell_file = source_dir / "cases" / "cells" / "sphere.toml"
    labels = micro_labels(program, cell_file, tmp_path)
    cell = lamina.Cell.from_array(labels, phases_of(cell_file))
    p = lamina.homogenize(cell, threads=1).provenance
    assert cell.source == "<array>" and p["cell_file"] == "<array>"
    assert "8 x 8 x 8 voxels" in p["cell_text"] and "used in place" in p["cell_text"]
    assert p["resolution"] == [8, 8, 8]
    # the checksum changes with one voxel
    other = labels.copy()
    other[0, 0, 0] = 1 - other[0, 0, 0]
    q = lamina.homogenize(lamina.Cell.from_array(other, phases_of(cell_file)), threads=1)
    assert q.provenance["cell_text"] != p["cell_text"]
