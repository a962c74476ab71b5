"""Fixtures shared by the Python module's tests (tests/python/CMakeLists.txt
sets PYTHONPATH to the build tree's package, LAMINA_BIN to its programs and
LAMINA_SOURCE_DIR to the source tree)."""

import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("LAMINA_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
BIN_DIR = pathlib.Path(os.environ.get("LAMINA_BIN", SOURCE_DIR / "build" / "bin"))


@pytest.fixture
def source_dir() -> pathlib.Path:
    """The source tree (cases/, materials/catalog.toml)."""
    return SOURCE_DIR


@pytest.fixture
def library_path(tmp_path, monkeypatch) -> pathlib.Path:
    """A fresh, empty library file path for one test; LAMINA_LIBRARY points
    to it (for the module and for the programs alike)."""
    path = tmp_path / "library.toml"
    monkeypatch.setenv("LAMINA_LIBRARY", str(path))
    monkeypatch.setenv("LAMINA_CATALOG", str(SOURCE_DIR / "materials" / "catalog.toml"))
    return path


@pytest.fixture
def program():
    """program(name, *args, cwd=None) runs build/bin/<name> and returns its
    CompletedProcess (stdout and stderr as text); a non-zero exit fails the
    test with the program's stderr."""

    def run(name, *args, cwd=None, check=True):
        proc = subprocess.run([str(BIN_DIR / name), *map(str, args)], cwd=cwd,
                              capture_output=True, text=True)
        if check and proc.returncode != 0:
            pytest.fail(f"{name} {' '.join(map(str, args))} exited {proc.returncode}:\n"
                        f"{proc.stderr}")
        return proc

    return run
