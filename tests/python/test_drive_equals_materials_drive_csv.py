"""lamina.drive is `materials drive` without the file: the same columns in
the CSV's order and, read back from the CSV's 17 significant digits, the
same doubles bit for bit, for the catalog's GVBO law, an elastic catalog
entry (with the lateral Newton of the stress paths), a library layup and a
reduced-order library entry."""

import lamina
import numpy as np
import pytest

HEADER = ("t,eps_xx,eps_yy,eps_zz,eps_xy,eps_yz,eps_xz,"
          "sig_xx,sig_yy,sig_zz,sig_xy,sig_yz,sig_xz").split(",")


def read_csv(path):
    """The CSV as column -> array, after checking that every field is its
    double printed with 17 significant digits (so the parse is exact)."""
    lines = path.read_text().splitlines()
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:]]
    for row in rows:
        for field in row:
            assert field == "%.17g" % float(field), field
    values = np.array([[float(f) for f in row] for row in rows])
    return header, {name: values[:, i] for i, name in enumerate(header)}


def program_drive(program, tmp_path, name, path, rate, to, steps, unload, kinematics, *extra):
    out = tmp_path / "drive.csv"
    args = ["materials", "drive", name, "--path", path, "--rate", repr(rate), "--to", repr(to),
            "--steps", str(steps), "--kinematics", kinematics, "--out", out, *extra]
    if unload:
        args.append("--unload")
    program(*args)
    return read_csv(out)


def assert_bit_for_bit(ours, header, theirs):
    assert list(ours) == header == HEADER
    for name in header:
        assert ours[name].dtype == np.float64, name
        assert ours[name].tobytes() == theirs[name].tobytes(), name


CASES = [
    ("polyurea-gvbo", "uniaxial-strain", 2.6e3, 0.3, 60, True, "finite"),
    ("polyurea-gvbo", "uniaxial-stress", 1e2, 0.2, 40, False, "small"),
    ("table1-anisotropic", "uniaxial-stress", 1.0, 0.05, 30, True, "finite"),
    ("mil-a46100", "shear", 10.0, 0.01, 20, False, "finite"),
]


@pytest.mark.parametrize("name,path,rate,to,steps,unload,kinematics", CASES)
def test_a_catalog_law_gives_the_programs_csv(library_path, program, tmp_path, name, path, rate,
                                              to, steps, unload, kinematics):
    ours = lamina.drive(name, path=path, rate=rate, to=to, steps=steps, unload=unload,
                        kinematics=kinematics)
    header, theirs = program_drive(program, tmp_path, name, path, rate, to, steps, unload,
                                   kinematics)
    assert_bit_for_bit(ours, header, theirs)
    assert len(ours["t"]) == (2 * steps if unload else steps) + 1
    assert np.abs(ours["sig_xx"]).max() > 0  # a loaded point, not two rows of zeros


def test_a_library_layup_named_with_library_gives_the_programs_csv(tmp_path, program,
                                                                   source_dir):
    """A library named by argument (not $LAMINA_LIBRARY): a layup entry is
    the linear law of its C, as the program drives it."""
    lib_file = tmp_path / "other.toml"
    catalog = source_dir / "materials" / "catalog.toml"
    lib = lamina.Library(lib_file, catalog=catalog)
    lib.add_from_catalog("X", "table1-anisotropic")
    lib.layup("cross", [("X", 0, 1e-3), ("X", 90, 1e-3)])
    ours = lamina.drive("cross", path="biaxial-stress", rate=5.0, to=0.02, steps=10,
                        library=lib_file, catalog=catalog)
    header, theirs = program_drive(program, tmp_path, "cross", "biaxial-stress", 5.0, 0.02, 10,
                                   False, "finite", "--library", lib_file, "--catalog", catalog)
    assert_bit_for_bit(ours, header, theirs)


def test_a_reduced_order_entry_gives_the_programs_csv(library_path, program, tmp_path,
                                                      source_dir):
    cell = source_dir / "cases" / "cells" / "polyurea-two-scale.toml"
    program("homogenize", cell, "--name", "rom", "--reduced-order", "--set", "cell.resolution=8")
    ours = lamina.drive("rom", path="confined", rate=2.6e3, to=0.2, steps=30,
                        kinematics="small")
    header, theirs = program_drive(program, tmp_path, "rom", "confined", 2.6e3, 0.2, 30, False,
                                   "small")
    assert_bit_for_bit(ours, header, theirs)
