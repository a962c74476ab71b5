"""Cell.from_array uses the label array in place when it can and copies it
once otherwise (Cell.copied says which): an int32, C-ordered array whose
ids are 0..P-1 is the cell's phase map (phase_map() shares its memory and
is a read-only view whose base is the Cell); Fortran order, int64 or ids
{1, 2} are copied and mapped to phase indices 0..P-1, with the same cell."""

import gc
import weakref

import lamina
import numpy as np
import pytest

PHASES = [dict(name="a", law="isotropic", E=1e9, nu=0.3, density=1000.0),
          dict(name="b", law="isotropic", E=3e9, nu=0.25, density=2000.0)]


def labels_int32():
    rng = np.random.default_rng(7)
    return rng.integers(0, 2, size=(6, 5, 4)).astype(np.int32)


def test_int32_c_order_is_used_in_place():
    labels = labels_int32()
    cell = lamina.Cell.from_array(labels, dict(enumerate(PHASES)))
    assert not cell.copied
    view = cell.phase_map()
    assert np.shares_memory(view, labels)
    assert view.base is cell
    assert not view.flags.writeable
    assert view.shape == (6, 5, 4) and cell.resolution == (6, 5, 4)
    assert np.array_equal(view, labels)
    with pytest.raises(ValueError):
        view[0, 0, 0] = 1
    counted = np.bincount(labels.ravel(), minlength=2) / labels.size
    assert list(cell.phase_fractions.values()) == list(counted)


def test_the_cell_keeps_the_array_alive():
    labels = labels_int32()
    expected = labels.copy()
    cell = lamina.Cell.from_array(labels, dict(enumerate(PHASES)))
    del labels
    gc.collect()
    assert np.array_equal(cell.phase_map(), expected)


@pytest.mark.parametrize("how", ["fortran", "int64", "ids 1 and 2", "list", "uint8 strided"])
def test_other_arrays_are_copied_once_and_mapped(how):
    labels = labels_int32()
    phases = dict(enumerate(PHASES))
    if how == "fortran":
        given = np.asfortranarray(labels)
    elif how == "int64":
        given = labels.astype(np.int64)
    elif how == "ids 1 and 2":
        given, phases = labels + 1, {1: PHASES[0], 2: PHASES[1]}
    elif how == "list":
        given = labels.tolist()
    else:
        given = np.repeat(labels.astype(np.uint8), 2, axis=1)[:, ::2, :]
    cell = lamina.Cell.from_array(given, phases)
    assert cell.copied
    assert not np.shares_memory(cell.phase_map(), np.asarray(given))
    assert np.array_equal(cell.phase_map(), labels)
    assert cell.phase_map().dtype == np.int32
    assert cell.phase_names == ["a", "b"]


def test_changed_labels_are_refused_before_a_solve():
    labels = labels_int32()
    cell = lamina.Cell.from_array(labels, dict(enumerate(PHASES)))
    labels[0, 0, 0] = 1 - labels[0, 0, 0]  # the cell reads the array in place
    with pytest.raises(lamina.InputError, match="changed after Cell.from_array"):
        lamina.homogenize(cell, threads=1)
    labels[0, 0, 0] = 1 - labels[0, 0, 0]
    assert lamina.homogenize(cell, threads=1).C[0, 0] > 0
