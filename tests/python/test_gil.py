"""Long calls release the GIL: while lamina.homogenize and
lamina.membrane.run compute in one thread, another Python thread keeps
running. With the GIL held for the whole call, the watching thread could
take no step between the call's first bytecode switch and its return (at
most a couple); with it released, it steps every half millisecond of the
call."""

import threading
import time

import lamina
import pytest


def steps_beside(call):
    """Runs call() in a thread; @return (the watcher's loop count while it
    ran, the call's duration in s)."""
    errors = []

    def target():
        try:
            call()
        except BaseException as e:  # reported below
            errors.append(e)

    worker = threading.Thread(target=target)
    t0 = time.perf_counter()
    worker.start()
    steps = 0
    while worker.is_alive():
        steps += 1
        time.sleep(0.0005)
    duration = time.perf_counter() - t0
    if errors:
        raise errors[0]
    return steps, duration


def assert_released(steps, duration):
    # A call shorter than 0.1 s proves little either way: the cell or case
    # below is sized for a second or so at one thread.
    assert duration > 0.1, f"call too short to tell ({duration:.3f} s)"
    # Even on a loaded machine a thread that holds no lock takes a step per
    # few ms; 10 steps in the call is a bound far below the hundreds a
    # release gives and far above the 1-2 a held GIL allows.
    assert steps >= 10, f"{steps} steps of the other thread in {duration:.2f} s"


def test_homogenize_releases_the_gil(source_dir):
    cell = lamina.Cell.from_file(source_dir / "cases" / "cells" / "sphere.toml",
                                 set={"cell.resolution": 48})
    assert_released(*steps_beside(lambda: lamina.homogenize(cell, threads=1)))


def test_membrane_run_releases_the_gil(source_dir):
    case = source_dir / "cases" / "membrane" / "case1.toml"
    assert_released(*steps_beside(
        lambda: lamina.membrane.run(case, set={"mesh.nx": 121}, threads=1)))


def test_library_writes_wait_for_the_lock_without_the_gil(library_path):
    # Another process holds the library's lock (flock on <library>.lock, as
    # the programs take it) for 0.5 s: each write waits for it, and while it
    # waits the other Python thread keeps running.
    import subprocess
    import sys
    lib = lamina.Library(library_path)
    holder = ("import fcntl, sys, time\n"
              "f = open(sys.argv[1], 'a')\n"
              "fcntl.flock(f, fcntl.LOCK_EX)\n"
              "print('locked', flush=True)\n"
              "time.sleep(0.5)\n")
    writes = [lambda: lib.add_from_catalog("glass", "e-glass"),
              lambda: lib.layup("ply2", [("glass", 0.0, 1e-3), ("glass", 90.0, 1e-3)]),
              lambda: lib.remove("ply2")]
    for write in writes:
        proc = subprocess.Popen([sys.executable, "-c", holder, str(library_path) + ".lock"],
                                stdout=subprocess.PIPE, text=True)
        assert proc.stdout.readline().strip() == "locked"
        steps, duration = steps_beside(write)
        proc.wait()
        assert duration > 0.3, f"the write did not wait for the lock ({duration:.3f} s)"
        assert_released(steps, duration)
    assert "glass" in lib and "ply2" not in lib
