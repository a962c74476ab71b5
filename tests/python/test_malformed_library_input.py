"""Bad input to lamina.Library: a malformed library file (InputError with
its file and line), unknown names, bad plies, formats and arguments; each a
lamina.InputError naming what is wrong (a missing entry under lib[name]: a
KeyError, the Mapping's), never a crash, and nothing written."""

import lamina
import pytest


def input_error(call, *args, **kw):
    with pytest.raises(lamina.InputError) as info:
        call(*args, **kw)
    assert isinstance(info.value, ValueError)
    return info.value


@pytest.mark.parametrize("text,line", [
    ('[lamina]\nformat = "lamina-materials-library"\nversion = 1\n\n[materials."X"\n', 5),
    ('[lamina]\nformat = "lamina-materials-library"\nversion = 1\ncolour = "red"\n', 4),
    ('[lamina]\nformat = "something-else"\nversion = 1\n', 2),
])
def test_a_malformed_library_file_names_its_file_and_line(library_path, text, line):
    library_path.write_text(text)
    e = input_error(lamina.Library)
    assert e.file == str(library_path) and e.line == line, str(e)
    assert input_error(lamina.drive, "polyurea-gvbo", steps=2).file == str(library_path)


def test_a_file_broken_after_the_library_was_made_is_reported_at_the_next_access(library_path):
    lib = lamina.Library()
    library_path.write_text("not toml at all [\n")
    for call in (lambda: lib["X"], lambda: "X" in lib, lambda: len(lib), lambda: list(lib)):
        e = input_error(call)
        assert e.file == str(library_path) and e.line == 1


def test_a_missing_entry_is_a_key_error_naming_it_and_the_file(library_path):
    lib = lamina.Library()
    lib.add_from_catalog("X", "table1-anisotropic")
    with pytest.raises(KeyError) as info:
        lib["Y"]
    assert "'Y'" in str(info.value) and str(library_path) in str(info.value)
    with pytest.raises(KeyError):
        lib[3]
    assert 3 not in lib and lib.get("Y") is None
    e = input_error(lib.export, "Y")
    assert e.key == "Y" and str(library_path) in str(e)
    assert input_error(lib.remove, "Y").key == "Y"


def test_add_with_something_else_than_a_homogenize_result_is_refused(library_path):
    lib = lamina.Library()
    for result in (None, {"C": [[0.0] * 6] * 6}, "result"):
        input_error(lib.add, "H", result)
    assert len(lib) == 0 and not library_path.exists()


def test_bad_names_and_catalog_keys(library_path):
    lib = lamina.Library()
    e = input_error(lib.add_from_catalog, "X", "no-such-key")
    assert "'no-such-key'" in str(e)
    assert "name" in str(input_error(lib.add_from_catalog, "bad name", "e-glass")).lower()
    assert input_error(lib.add_from_catalog, 7, "e-glass").key == "name"
    lib.add_from_catalog("X", "e-glass")
    e = input_error(lib.add_from_catalog, "X", "aramid")  # no overwrite
    assert "already" in e.message
    lib.add_from_catalog("X", "aramid", overwrite=True)
    assert lib["X"]["provenance"]["catalog_key"] == "aramid"


@pytest.mark.parametrize("plies,key", [
    ("X:0:1e-3", "plies"),
    ([("X", 0)], "plies[0]"),
    ([("X", 0, 1e-3), ["X", "ninety", 1e-3]], "plies[1].angle_deg"),
    ([(3, 0, 1e-3)], "plies[0].material"),
    ([("X", 0, float("nan"))], "plies[0].thickness"),
])
def test_malformed_plies_are_named(library_path, plies, key):
    lib = lamina.Library()
    lib.add_from_catalog("X", "e-glass")
    assert input_error(lib.layup, "L", plies).key == key
    assert "L" not in lib


def test_plies_the_layup_refuses(library_path):
    lib = lamina.Library()
    lib.add_from_catalog("X", "e-glass")
    assert "no-such" in str(input_error(lib.layup, "L", [("no-such", 0, 1e-3)]))
    assert "thickness" in str(input_error(lib.layup, "L", [("X", 0, -1e-3)]))
    assert "angle" in str(input_error(lib.layup, "L", [("X", 400, 1e-3)]))
    assert "at least one ply" in str(input_error(lib.layup, "L", []))
    assert list(lib) == ["X"]


def test_an_unknown_export_format_lists_the_formats(library_path):
    lib = lamina.Library()
    lib.add_from_catalog("X", "e-glass")
    e = input_error(lib.export, "X", "nastran")
    assert e.key == "format" and "abaqus" in e.message


def test_paths_that_are_not_paths(tmp_path):
    assert input_error(lamina.Library, 3).key == "path"
    assert input_error(lamina.Library, "").key == "path"
    assert input_error(lamina.Library, tmp_path / "l.toml", catalog=1.5).key == "catalog"
