"""Bad arguments of lamina.drive: each a lamina.InputError (a ValueError)
naming what is wrong, raised before anything is computed; never a crash."""

import math

import lamina
import pytest

ISOTROPIC = {"law": "isotropic", "E": 1e9, "nu": 0.3}


def error_of(material="polyurea-gvbo", **kw):
    with pytest.raises(lamina.InputError) as info:
        lamina.drive(material, **kw)
    assert isinstance(info.value, ValueError)
    return info.value


def test_an_unknown_material_name_is_named_with_where_it_was_looked_for(library_path):
    e = error_of("no-such-material")
    assert e.key == "no-such-material"
    assert "unknown material 'no-such-material'" in str(e)
    assert str(library_path) in str(e) and "catalog" in str(e)


def test_an_unknown_path_name_lists_the_paths():
    e = error_of(path="uniaxial")
    assert e.key == "path" and "'uniaxial'" in e.message and "uniaxial-strain" in e.message


@pytest.mark.parametrize("rate", [math.nan, -1.0, 0.0, math.inf, 1e-300, "fast", None])
def test_a_rate_that_is_not_a_positive_finite_number_is_refused(rate):
    e = error_of(rate=rate)
    assert e.key == "rate"


@pytest.mark.parametrize("to", [0.0, -0.1, math.nan, math.inf])
def test_a_final_strain_that_is_not_positive_is_refused(to):
    e = error_of(to=to)
    assert e.key == "to"


def test_confined_compression_to_one_is_refused():
    e = error_of(path="confined", to=1.0)
    assert e.key == "to" and "zero volume" in e.message


@pytest.mark.parametrize("steps", [0, -3, 10**9, 2.5, "10", True])
def test_steps_outside_the_programs_range_or_not_an_int_are_refused(steps):
    assert error_of(steps=steps).key == "steps"


def test_an_unknown_kinematics_is_refused():
    e = error_of(kinematics="large")
    assert e.key == "kinematics" and "'small'" in e.message


def test_an_unknown_key_in_a_law_dict_is_named():
    e = error_of(dict(ISOTROPIC, Young=2e9))
    assert e.key == "material.Young"
    assert "isotropic" in e.message
    e = error_of(dict(ISOTROPIC, law="gvbo", gvbo={"Et": 1e6, "bogus": 1}))
    assert e.key.startswith("material.gvbo.")


def test_a_law_dict_with_a_bad_law_or_value_is_named():
    assert error_of({"law": "plastic", "E": 1e9, "nu": 0.3}).key == "material.law"
    assert error_of({"law": "isotropic", "E": -1e9, "nu": 0.3}).key == "material.E"
    assert error_of({"law": "isotropic", "E": 1e9, "nu": 0.5}).key == "material.nu"
    assert error_of({"law": "isotropic", "E": 1e9}).key == "material.nu"  # missing
    assert error_of({"law": "isotropic", "E": "stiff", "nu": 0.3}).key == "material.E"
    assert error_of({"law": "void"}).key == "material.law"  # a pore is no point law
    assert error_of({"law": "isotropic", "E": 1e9, "nu": 0.3, 5: 1}).key == "material"


def test_a_material_of_another_type_is_refused():
    assert error_of(3.5).key == "material"
    assert error_of(["polyurea-gvbo"]).key == "material"


def test_library_and_catalog_must_be_paths(tmp_path):
    assert error_of(library=42).key == "library"
    assert error_of(catalog=b"\0").key == "catalog"
    # a catalog file that is not a catalog: its own file named
    bad = tmp_path / "catalog.toml"
    bad.write_text("[x]\nlaw = \n")
    e = error_of(catalog=bad)
    assert e.file == str(bad) and e.line == 2
