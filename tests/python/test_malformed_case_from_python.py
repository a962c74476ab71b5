"""Bad input to lamina.membrane.run and lamina.blast: each a
lamina.InputError (a ValueError) naming what is wrong, never a crash of the
interpreter, and nothing computed; blast's messages are the program's."""

import math
import tomllib

import pytest

import lamina


@pytest.fixture
def doc(source_dir):
    with open(source_dir / "cases" / "membrane" / "case1.toml", "rb") as f:
        return tomllib.load(f)


def raises_input(call, *needles, key=None):
    """Runs @p call; asserts it raises lamina.InputError whose text holds every needle."""
    with pytest.raises(lamina.InputError) as info:
        call()
    assert isinstance(info.value, ValueError)
    for needle in needles:
        assert needle in str(info.value), str(info.value)
    if key is not None:
        assert info.value.key == key
    return info.value


def test_dict_case_with_an_unknown_key_names_it(doc, tmp_path):
    doc["time"]["dtt"] = 1.0e-5
    e = raises_input(lambda: lamina.membrane.run(doc, out=tmp_path / "out"), "unknown key",
                     key="time.dtt")
    assert e.file == "<dict>"
    assert not (tmp_path / "out").exists()  # refused before anything is written


def test_dict_case_with_a_value_of_no_toml_form_names_its_key(doc):
    doc["mesh"]["Lx"] = object()
    raises_input(lambda: lamina.membrane.run(doc), "no TOML form", key="mesh.Lx")


def test_missing_case_file(tmp_path):
    missing = tmp_path / "nothere.toml"
    e = raises_input(lambda: lamina.membrane.run(missing), "case file not found")
    assert e.file == str(missing)


def test_case_of_another_type():
    raises_input(lambda: lamina.membrane.run(42), "case must be", key="case")


def test_set_with_an_unknown_key(doc):
    raises_input(lambda: lamina.membrane.run(doc, set={"time.nonsense": 1}), "unknown key",
                 "--set time.nonsense=1", key="time.nonsense")


def test_set_that_is_not_a_dict(doc):
    raises_input(lambda: lamina.membrane.run(doc, set=[("time.dt", 1e-5)]), "must be a dict",
                 key="set")


@pytest.mark.parametrize("where", ["dict", "set"])
def test_negative_time_step(doc, where):
    if where == "dict":
        doc["time"]["dt"] = -1.0e-5
        call = lambda: lamina.membrane.run(doc)  # noqa: E731
    else:
        call = lambda: lamina.membrane.run(doc, set={"time.dt": -1.0e-5})  # noqa: E731
    raises_input(call, "dt must be > 0", key="time.dt")


@pytest.mark.parametrize("fields,key", [(["a"], "fields[0]"), ([1e-4, math.nan], "fields[1]"),
                                        (1.0e-4, "fields"), ("0.1", "fields")])
def test_fields_that_are_not_times(doc, fields, key):
    raises_input(lambda: lamina.membrane.run(doc, fields=fields), key=key)


def test_threads_out_of_range_and_progress_not_callable(doc):
    raises_input(lambda: lamina.membrane.run(doc, threads=-1), key="threads")
    raises_input(lambda: lamina.membrane.run(doc, progress=3), "callable", key="progress")


def test_output_folder_that_is_a_file(doc, tmp_path):
    f = tmp_path / "file"
    f.write_text("keep me")
    raises_input(lambda: lamina.membrane.run(doc, out=f), "not a directory", key="out")
    assert f.read_text() == "keep me"


@pytest.mark.parametrize("args,cli,needle", [
    ((-1.0, 10.0), ["--charge", "-1", "--distance", "10"], "charge must be positive"),
    ((1.0, math.nan), ["--charge", "1", "--distance", "nan"], "distance from the charge"),
])
def test_blast_refuses_what_the_program_refuses_with_its_message(program, args, cli, needle):
    e = raises_input(lambda: lamina.blast(*args), needle)
    proc = program("membrane", "blast", *cli, "--json", check=False)
    assert proc.returncode != 0
    assert str(e) in proc.stderr  # the program's line: "membrane: error: <the same text>"


def test_blast_unknown_burst_names_the_choices():
    raises_input(lambda: lamina.blast(1.0, 10.0, burst="airburst"), "airburst", "hemispherical",
                 "spherical", key="burst")


def test_blast_charge_that_is_no_number():
    raises_input(lambda: lamina.blast("1", 10.0), "expected a number", key="charge")
