"""lamina's exceptions: the hierarchy the module promises (bad input is a
ValueError, a divergence an ArithmeticError, both lamina.Error), and the
programs' context (file, line, key) carried as attributes."""

import lamina
import pytest


def test_input_error_is_a_value_error_and_a_lamina_error():
    assert issubclass(lamina.InputError, ValueError)
    assert issubclass(lamina.InputError, lamina.Error)
    assert issubclass(lamina.DivergenceError, lamina.Error)
    assert issubclass(lamina.DivergenceError, ArithmeticError)
    assert not issubclass(lamina.DivergenceError, ValueError)


def test_error_carries_the_context_it_was_given():
    e = lamina.InputError("case.toml:3: key 'time.dt': must be > 0", message="must be > 0",
                          file="case.toml", line=3, key="time.dt")
    assert (e.file, e.line, e.key, e.message) == ("case.toml", 3, "time.dt", "must be > 0")
    assert str(e) == "case.toml:3: key 'time.dt': must be > 0"
    with pytest.raises(ValueError):
        raise e


def test_version_is_the_projects():
    assert lamina.__version__.count(".") == 2
