"""Bad input to Cell.from_array, homogenize and homogenize_path: each is a
lamina.InputError (a ValueError) naming what is wrong, and the interpreter
carries on (a crash would end the test run)."""

import lamina
import numpy as np
import pytest

PHASES = {0: dict(name="a", law="isotropic", E=1e9, nu=0.3, density=1000.0),
          1: dict(name="b", law="isotropic", E=3e9, nu=0.25, density=2000.0)}


def labels():
    out = np.zeros((4, 4, 4), dtype=np.int32)
    out[:2] = 1
    return out


def refused(match, key=None, **kwargs):
    args = dict(labels=labels(), phases=PHASES)
    args.update(kwargs)
    with pytest.raises(lamina.InputError, match=match) as info:
        lamina.Cell.from_array(**args)
    assert isinstance(info.value, ValueError)
    if key is not None:
        assert info.value.key == key
    return info.value


def test_float_dtype():
    refused("integers .*float64", "labels", labels=labels().astype(np.float64))


def test_bool_dtype():
    refused("integers .*bool", "labels", labels=labels().astype(bool))


def test_2d_array():
    refused("3-dimensional.*2 dimension", "labels", labels=np.zeros((4, 4), dtype=np.int32))


def test_empty_array():
    refused("empty", "labels", labels=np.zeros((0, 4, 4), dtype=np.int32))


def test_an_axis_of_one_voxel():
    refused("2 to 4096", "labels", labels=np.zeros((4, 1, 4), dtype=np.int32))


@pytest.mark.parametrize("bad", [None, "abc", 3.5, [[[0, 1], [1]], [[0]]], [[[0.5, 1.0]]]])
def test_labels_not_an_integer_array(bad):
    refused("labels", "labels", labels=bad)


def test_nested_lists_of_integers_are_fine():
    cell = lamina.Cell.from_array(labels().tolist(), PHASES)
    assert cell.copied and cell.resolution == (4, 4, 4)


@pytest.mark.parametrize("size", [float("nan"), [1e-3, float("nan"), 1e-3]])
def test_nan_size(size):
    refused("finite", "size", size=size)


@pytest.mark.parametrize("size", [-1e-3, [1e-3, -1e-3, 1e-3], 0.0])
def test_negative_size(size):
    refused("positive", "size", size=size)


def test_size_not_in_metres():
    refused("metres", "size", size=5.0)


@pytest.mark.parametrize("size", ["1e-3", [1e-3, 1e-3], True])
def test_size_of_another_kind(size):
    refused("", "size", size=size)


def test_an_id_with_no_phase_is_named():
    bad = labels()
    bad[0, 0, 0] = 7
    e = refused("7 \\(1 voxel\\)", "phases", labels=bad)
    assert "0, 1" in str(e)  # the ids the dict has


def test_an_id_with_no_phase_in_a_copied_array():
    refused("-3 \\(64 voxels\\)", "phases", labels=np.full((4, 4, 4), -3, dtype=np.int16))


def test_unknown_key_in_a_phase_is_named():
    phases = {0: PHASES[0], 1: dict(PHASES[1], stiffnes=3)}
    e = refused("unknown key", "phases[1].stiffnes", phases=phases)
    assert "stiffnes" in str(e)


def test_missing_key_in_a_phase_is_named():
    phases = {0: PHASES[0], 5: {k: v for k, v in PHASES[1].items() if k != "E"}}
    bad = labels() * 5
    refused("", "phases[5].E", labels=bad, phases=phases)


def test_an_id_key_that_differs_from_the_dict_key():
    refused("leave id out", "phases[1].id", phases={0: PHASES[0], 1: dict(PHASES[1], id=4)})


@pytest.mark.parametrize("phases", [{}, [PHASES[0]], {"0": PHASES[0]}, {0: "a"},
                                    {0: dict(PHASES[0], E=[1, "x"])}])
def test_phases_of_another_shape(phases):
    refused("", labels=np.zeros((2, 2, 2), dtype=np.int32), phases=phases)


def test_unknown_catalog_entry():
    refused("no catalog entry", "phases[0].catalog",
            phases={0: dict(name="a", catalog="no-such-material")},
            labels=np.zeros((2, 2, 2), dtype=np.int32))


def test_bad_arguments_of_homogenize():
    cell = lamina.Cell.from_array(labels(), PHASES)
    for kwargs, key in [(dict(tol=-1.0), "tol"), (dict(tol=float("nan")), "tol"),
                        (dict(threads=-1), "threads"), (dict(threads=1.5), "threads"),
                        (dict(J=0.0), "J"), (dict(progress=3), "progress")]:
        with pytest.raises(lamina.InputError) as info:
            lamina.homogenize(cell, **kwargs)
        assert info.value.key == key, kwargs
    with pytest.raises(lamina.InputError, match="lamina.Cell"):
        lamina.homogenize(labels())


def test_bad_arguments_of_homogenize_path():
    cell = lamina.Cell.from_array(labels(), PHASES)
    for kwargs, key in [(dict(path="twist"), "path"), (dict(rate=0.0), "rate"),
                        (dict(rate=float("inf")), "rate"), (dict(to=-0.1), "to"),
                        (dict(path="confined", to=1.0), "to"), (dict(steps=0), "steps"),
                        (dict(steps=2.5), "steps"), (dict(unload="yes"), "unload")]:
        with pytest.raises(lamina.InputError) as info:
            lamina.homogenize_path(cell, **kwargs)
        assert info.value.key == key, kwargs


def test_a_void_phase_has_no_path():
    phases = {0: PHASES[0], 1: dict(name="pore", law="void")}
    cell = lamina.Cell.from_array(labels(), phases)
    with pytest.raises(lamina.InputError, match="void"):
        lamina.homogenize_path(cell, to=0.01, steps=1)


def test_bad_cell_file_arguments(tmp_path):
    with pytest.raises(lamina.InputError, match="path"):
        lamina.Cell.from_file(3)
    with pytest.raises(lamina.InputError):
        lamina.Cell.from_file(tmp_path / "missing.toml")
    with pytest.raises(lamina.InputError, match="set"):
        lamina.Cell.from_file(tmp_path / "missing.toml", set=["cell.resolution=8"])
