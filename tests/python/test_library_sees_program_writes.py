"""A lamina.Library caches nothing: entries the `materials` program adds or
removes after the Library was made are seen at the next access, and
writers in several processes and in Python at once all land (the
programs' lock and atomic replace serialize them)."""

import os
import subprocess

import lamina
from conftest import BIN_DIR


def test_a_library_sees_what_the_program_writes_after_it_was_made(library_path, program):
    lib = lamina.Library()
    assert len(lib) == 0 and list(lib) == []
    program("materials", "add", "X", "--from-catalog", "table1-anisotropic")
    assert "X" in lib and list(lib) == ["X"] and len(lib) == 1
    assert lib["X"]["kind"] == "catalog"
    diagonal = [1e9 if i == j else 0.0 for i in range(6) for j in range(i, 6)]  # C11,...,C66
    program("materials", "add", "Y", "--constants", ",".join(map(repr, diagonal)),
            "--density", "1000")
    assert sorted(lib.keys()) == ["X", "Y"]
    assert lib["Y"]["C"][0, 0] == 1e9 and lib["Y"]["density"] == 1000.0
    program("materials", "remove", "X")
    assert "X" not in lib and list(lib) == ["Y"]
    assert lib.get("X") is None and lib.get("Y")["kind"] == "constants"


def test_writers_in_processes_and_in_python_at_once_all_land(library_path):
    """Eight `materials add` processes started together and eight
    Library.add_from_catalog calls while they run: all sixteen entries are
    in the file afterwards (a lost update would drop some)."""
    env = dict(os.environ)
    procs = [subprocess.Popen([str(BIN_DIR / "materials"), "add", f"p{i}", "--from-catalog",
                               "mil-a46100"], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True) for i in range(8)]
    lib = lamina.Library()
    for i in range(8):
        lib.add_from_catalog(f"y{i}", "e-glass")
    for p in procs:
        _, err = p.communicate(timeout=60)
        assert p.returncode == 0, err
    assert sorted(lib) == sorted([f"p{i}" for i in range(8)] + [f"y{i}" for i in range(8)])
    assert lamina.Library(library_path)["p3"]["provenance"]["program"] == "materials add"
