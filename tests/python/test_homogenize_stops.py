"""A long homogenization stops when asked: a progress callback that raises
stops lamina.homogenize and homogenize_path at their next safe point (a CG
iteration) and its exception reaches the caller, the callback not being
called again; Ctrl-C (SIGINT, here sent by the callback itself) stops them
with KeyboardInterrupt before the last load case or step is reported."""

import os
import signal

import lamina
import pytest


class Stop(Exception):
    pass


def sphere(source_dir):
    return lamina.Cell.from_file(source_dir / "cases" / "cells" / "sphere.toml",
                                 set={"cell.resolution": 16})


def polyurea(source_dir):
    return lamina.Cell.from_file(source_dir / "cases" / "cells" / "polyurea.toml",
                                 set={"cell.resolution": 8})


def calls(source_dir):
    yield "homogenize", lambda p: lamina.homogenize(sphere(source_dir), threads=1, progress=p)
    yield "path", lambda p: lamina.homogenize_path(polyurea(source_dir), to=0.05, steps=50,
                                                   threads=1, progress=p)


@pytest.mark.parametrize("which", ["homogenize", "path"])
def test_a_raising_callback_stops_the_call(source_dir, which):
    call = dict(calls(source_dir))[which]
    seen = []

    def progress(done, total, label):
        seen.append((done, total, label))
        raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        call(progress)
    assert len(seen) == 1
    # the stop was for that call only: the next one runs to its end
    ends = []
    call(lambda done, total, label: ends.append(done == total))
    assert ends[-1]


@pytest.mark.parametrize("which", ["homogenize", "path"])
def test_ctrl_c_stops_the_call_before_its_end(source_dir, which):
    call = dict(calls(source_dir))[which]
    seen = []

    def progress(done, total, label):
        seen.append((done, total, label))
        if len(seen) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        call(progress)
    assert seen
    # the line's last update (done == total) is always reported to the
    # callback; a call that ran to its end would have reported it
    assert all(done < total for done, total, _ in seen), seen
    assert call(None) is not None  # and the next call is not stopped


def test_progress_reaches_the_end_without_a_stop(source_dir):
    seen = []
    lamina.homogenize_path(polyurea(source_dir), to=0.01, steps=3, threads=1,
                           progress=lambda d, t, l: seen.append((d, t, l)))
    assert seen[-1] == (3, 3, "path steps")
