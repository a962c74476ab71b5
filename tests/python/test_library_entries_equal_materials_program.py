"""lamina.Library reads and writes the library as the `materials` program
does: lib[name] is `materials show NAME --json` field by field (C and the
other 6x6 matrices as (6, 6) float64 arrays holding the very doubles the
program prints), entries that Python writes (add_from_catalog, layup,
remove) are what the program then shows and lists, and export() returns
the program's stdout byte for byte in every format."""

import json
import struct

import lamina
import numpy as np
import pytest

# every format `materials export --format` takes (materials/export.hpp)
FORMATS = ["json", "abaqus", "calculix", "lsdyna", "lsdyna-small"]
MATRICES = ("C", "dispersion")


def bits(x):
    return struct.pack("<d", x)


def assert_same(ours, theirs, where):
    """ours (lamina.Library's) equals theirs (json.loads of the program's
    output): same keys, same types, floats bit for bit, 6x6 matrices as
    (6, 6) float64 arrays equal to the program's rows bit for bit."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict), where
        assert list(ours) == list(theirs), where
        for key in theirs:
            if key in MATRICES:
                assert isinstance(ours[key], np.ndarray), f"{where}.{key}"
                assert ours[key].dtype == np.float64 and ours[key].shape == (6, 6)
                assert ours[key].tobytes() == np.array(theirs[key], dtype=np.float64).tobytes(), \
                    f"{where}.{key}"
            else:
                assert_same(ours[key], theirs[key], f"{where}.{key}")
    elif isinstance(theirs, list):
        assert isinstance(ours, list) and len(ours) == len(theirs), where
        for i, (a, b) in enumerate(zip(ours, theirs)):
            assert_same(a, b, f"{where}[{i}]")
    elif isinstance(theirs, float):
        assert isinstance(ours, float) and bits(ours) == bits(theirs), (where, ours, theirs)
    else:
        assert type(ours) is type(theirs) and ours == theirs, (where, ours, theirs)


def show(program, name):
    return json.loads(program("materials", "show", name, "--json").stdout)


def test_an_entry_the_program_added_is_what_show_json_prints(library_path, program):
    program("materials", "add", "X", "--from-catalog", "table1-anisotropic")
    lib = lamina.Library()
    assert lib.path == str(library_path)
    entry = lib["X"]
    theirs = show(program, "X")
    assert_same(entry, theirs, "X")
    assert entry["kind"] == "catalog"
    # the comparison covers every field: the helper failing on a changed bit
    tampered = json.loads(json.dumps(theirs))
    tampered["C"][0][0] = np.nextafter(tampered["C"][0][0], np.inf)
    with pytest.raises(AssertionError):
        assert_same(entry, tampered, "X")


def test_python_writes_are_what_the_program_shows_and_lists(library_path, program):
    lib = lamina.Library(library_path)
    lib.add_from_catalog("pu", "polyurea-gvbo")
    lib.add_from_catalog("X", "table1-anisotropic")
    lib.layup("quasi", [("X", 0, 1e-3), ("X", 45, 1e-3), ("X", -45, 1e-3), ("X", 90, 1e-3)])
    for name in ("pu", "X", "quasi"):
        assert_same(lib[name], show(program, name), name)
    assert lib["X"]["provenance"]["catalog_key"] == "table1-anisotropic"
    assert lib["quasi"]["provenance"]["program"] == "lamina.Library.layup"
    listed = json.loads(program("materials", "list", "--json").stdout)
    assert [e["name"] for e in listed] == list(lib) == ["X", "pu", "quasi"]
    lib.remove("pu")
    listed = json.loads(program("materials", "list", "--json").stdout)
    assert [e["name"] for e in listed] == list(lib) == ["X", "quasi"]
    assert len(lib) == 2 and "pu" not in lib


def test_a_layup_from_python_equals_the_programs_layup(library_path, program):
    """The same plies through `materials layup` and Library.layup give the
    same C, density and thickness, bit for bit (the same makeLayup)."""
    lib = lamina.Library()
    lib.add_from_catalog("X", "table1-anisotropic")
    plies = [("X", 0, 1e-3), ("X", 30, 2e-3), ("mil-a46100", -60, 0.5e-3)]
    lib.layup("py", plies)
    program("materials", "layup", "cli", *[f"--ply={m}:{a}:{t}" for m, a, t in plies])
    ours, theirs = lib["py"], lib["cli"]
    assert ours["C"].tobytes() == theirs["C"].tobytes()
    for key in ("density", "thickness", "plies", "engineering", "symmetry"):
        assert ours[key] == theirs[key], key


@pytest.mark.parametrize("fmt", FORMATS)
def test_export_is_the_programs_stdout_byte_for_byte(library_path, program, fmt):
    lib = lamina.Library()
    lib.add_from_catalog("X", "table1-anisotropic")
    lib.layup("lay-up", [("X", 0, 1e-3), ("X", 90, 2e-3)])
    for name in ("X", "lay-up"):
        text = lib.export(name, fmt)
        assert text == program("materials", "export", name, "--format", fmt).stdout
        assert text  # not two empty strings
    assert lib.export("X") == lib.export("X", "json")


def test_a_reduced_order_entry_is_what_show_json_prints(library_path, program, source_dir):
    """A reduced-order entry (homogenize --reduced-order on a small cell):
    lib[name] has the side file's counts that `show --json` adds
    (partitions per phase, state_doubles, nonlinear_partitions) and its
    phases' C, its dispersion as arrays."""
    cell = source_dir / "cases" / "cells" / "polyurea-two-scale.toml"
    program("homogenize", cell, "--name", "rom", "--reduced-order", "--set", "cell.resolution=8")
    lib = lamina.Library()
    entry = lib["rom"]
    assert_same(entry, show(program, "rom"), "rom")
    assert entry["kind"] == "reduced-order"
    assert [p["partitions"] for p in entry["phases"]] == [1, 1]
    assert all(p["C"].shape == (6, 6) for p in entry["phases"])
    assert entry["dispersion"].shape == (6, 6)
