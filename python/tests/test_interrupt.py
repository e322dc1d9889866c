"""Ctrl-C stops a run, a compare and a check within a fraction of a second: the step driver asks
Python's signal handlers every 0.1 s (dae/interface/interrupt.hpp), and KeyboardInterrupt is raised from
the call. Before, the signal waited for the whole call to end."""

import os
import signal
import threading
import time

import pytest

import condyn
from test_threads import long_chain

# The chain integrated to t = 400 takes several times the bound below without the poll: a call
# that ignored Ctrl-C would outlast the bound, one that honours it stops within a poll interval of
# the signal.
T_END = 400.0
SIGNAL_AFTER = 0.5  # seconds into the call
BOUND = 10.0  # seconds: the signal's delay, a poll interval, and a loaded machine's slack


def interrupted_after(call):
    """Seconds from the start of `call` to the KeyboardInterrupt a SIGINT raised in it."""
    timer = threading.Timer(SIGNAL_AFTER, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()
    return time.perf_counter() - start


def scene():
    s = long_chain("ggl")
    s["solve"]["t_end"] = T_END
    return s


def test_ctrl_c_stops_a_run():
    assert interrupted_after(lambda: condyn.run(scene())) < BOUND


def test_ctrl_c_stops_a_compare():
    assert interrupted_after(
        lambda: condyn.compare(scene(), tolerances=[1e-9], schemes=["ggl", "index1"])) < BOUND


def test_ctrl_c_stops_a_check():
    s = scene()
    s["check"] = [{"quantity": "drift_position", "max_abs": 1.0}]
    assert interrupted_after(lambda: condyn.check(s)) < BOUND


def test_a_run_after_an_interrupt_is_whole():
    interrupted_after(lambda: condyn.run(scene()))
    s = long_chain("ggl")
    assert condyn.run(s).t[-1] == s["solve"]["t_end"]


def test_ctrl_c_stops_a_run_writing_a_file_and_leaves_none(tmp_path):
    # The module keeps Python's signal handlers (the command's own would remove the temporary
    # file and end the interpreter): KeyboardInterrupt, and the temporary file removed by its
    # owner as the exception passes. The file named is not written: the rows are lost with the
    # Result, as in a run without `out`.
    assert interrupted_after(lambda: condyn.run(scene(), out=tmp_path / "r.h5")) < BOUND
    assert os.listdir(tmp_path) == []
