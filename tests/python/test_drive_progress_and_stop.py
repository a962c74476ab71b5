"""lamina.drive runs through LongCall: its progress callback sees the
steps (done, total) up to the total, and a callback that raises stops the
drive at the next step and its exception reaches the caller; Ctrl-C
(SIGINT) stops it with KeyboardInterrupt."""

import os
import signal
import threading

import lamina
import pytest


def test_progress_reports_steps_and_a_raising_callback_stops_the_drive():
    seen = []
    lamina.drive("polyurea-gvbo", steps=50, unload=True,
                 progress=lambda done, total, label: seen.append((done, total, label)))
    assert seen and seen[-1][:2] == (100, 100)
    assert all(total == 100 and 1 <= done <= 100 for done, total, _ in seen)

    class Stop(Exception):
        pass

    calls = []

    def stop(done, total, label):
        calls.append(done)
        raise Stop()

    with pytest.raises(Stop):
        lamina.drive("polyurea-gvbo", steps=100000, progress=stop)
    assert calls == [1]  # stopped at the step after the first report


def test_ctrl_c_stops_the_drive_with_keyboard_interrupt():
    """SIGINT while the point is driven (the programs' interrupt handling):
    KeyboardInterrupt at the next step, and Python's own SIGINT handler is
    back afterwards. Two million GVBO steps take seconds; the signal comes
    after 0.1 s (rows of a missed stop would still fit in 0.3 GB)."""
    timer = threading.Timer(0.1, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt, match="step"):
            lamina.drive("polyurea-gvbo", rate=1.0, to=0.5, steps=2_000_000)
    finally:
        timer.cancel()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
