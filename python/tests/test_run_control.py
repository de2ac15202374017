"""How a solve runs inside Python (python/python_run.hpp): Ctrl-C stops it with
KeyboardInterrupt within seconds, the GIL is released so other threads run meanwhile, the
progress callable sees the stages and may stop the run by raising, threads= applies to the
call only."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import bemshape
from support import icosphere

H0 = 0.3


def long_solve_mesh():
    """The geodesic ball of 20 480 faces (edge ~0.017): a solve of tens of seconds on two
    cores at max_edge=LONG_SOLVE_EDGE (the remesher leaves it nearly as it is)."""
    return icosphere(0.5, 5)


LONG_SOLVE_EDGE = 0.018


def test_ctrl_c_raises_keyboard_interrupt_within_seconds():
    V, F = long_solve_mesh()
    assembling = threading.Event()
    sent = []

    def interrupt_during_assembly():
        if assembling.wait(timeout=120):
            time.sleep(1.0)
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)

    def progress(stage, fraction):
        if stage.startswith("assemble"):
            assembling.set()

    thread = threading.Thread(target=interrupt_during_assembly)
    thread.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            bemshape.thickness(V, F, h0=H0, max_edge=LONG_SOLVE_EDGE, progress=progress)
    finally:
        assembling.set()
        thread.join()
    assert sent, "the solve never reached its assembly"
    delay = time.monotonic() - sent[0]
    assert delay < 3.0, f"stopped {delay:.1f} s after the signal"
    # The next call runs normally: the cancellation does not outlive the call.
    small_V, small_F = icosphere(0.5, 1)
    assert bemshape.thickness(small_V, small_F, h0=H0, max_edge=0.3)["statistics"]["min"] > 0


def test_exception_from_a_python_signal_handler_stops_the_solve():
    class Timeout(Exception):
        pass

    def on_alarm(signum, frame):
        raise Timeout()

    previous = signal.signal(signal.SIGALRM, on_alarm)
    V, F = long_solve_mesh()
    start = time.monotonic()
    signal.setitimer(signal.ITIMER_REAL, 2.0)
    try:
        with pytest.raises(Timeout):
            bemshape.thickness(V, F, h0=H0, max_edge=LONG_SOLVE_EDGE)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    # A handler of the user's own runs at the library's next progress report on the main
    # thread: those come seconds apart in the largest stages (up to about 5 s in this
    # H-matrix assembly on two busy cores), against minutes for the whole solve.
    assert time.monotonic() - start < 2.0 + 15.0


def test_other_threads_run_during_a_solve():
    V, F = icosphere(0.5, 3)  # 1280 faces: a dense solve of several seconds
    counts = []
    done = threading.Event()

    def count():
        n = 0
        while not done.is_set():
            n += 1
        counts.append(n)

    # A reference: how far the thread counts in the same time when the main thread sleeps
    # (sleep releases the GIL).
    thread = threading.Thread(target=count)
    start = time.monotonic()
    thread.start()
    bemshape.thickness(V, F, h0=H0)
    solve_seconds = time.monotonic() - start
    done.set()
    thread.join()
    during_solve = counts.pop()
    done.clear()
    thread = threading.Thread(target=count)
    thread.start()
    time.sleep(solve_seconds)
    done.set()
    thread.join()
    while_sleeping = counts.pop()
    # With the GIL held for the solve the thread would count almost nothing; released, it
    # counts at the rate of a free thread (less the CPU the solve's OpenMP threads take).
    assert during_solve > 0.1 * while_sleeping, (during_solve, while_sleeping)


def test_progress_sees_the_stages_and_an_exception_from_it_stops_the_run():
    V, F = icosphere(0.5, 2)
    seen = []
    bemshape.thickness(V, F, h0=H0, max_edge=0.15,
                       progress=lambda stage, fraction: seen.append((stage, fraction)))
    stages = [stage for stage, _ in seen]
    assert "assemble" in stages and "surface features" in stages
    assert all(0.0 <= fraction <= 1.0 for _, fraction in seen)

    class Stop(Exception):
        pass

    def stop_at_assembly(stage, fraction):
        if stage == "assemble":
            raise Stop(stage)

    with pytest.raises(Stop):
        bemshape.thickness(V, F, h0=H0, max_edge=0.15, progress=stop_at_assembly)
    with pytest.raises(ValueError, match="progress"):
        bemshape.thickness(V, F, h0=H0, max_edge=0.15, progress=42)


def test_threads_apply_to_the_call_only():
    V, F = icosphere(0.5, 1)
    before = bemshape.thickness(V, F, h0=H0, max_edge=0.3)
    one = bemshape.thickness(V, F, h0=H0, max_edge=0.3, threads=1)
    after = bemshape.thickness(V, F, h0=H0, max_edge=0.3)
    assert one["report"]["parameters"]["threads"] == 1
    assert after["report"]["parameters"]["threads"] == before["report"]["parameters"]["threads"]
    assert np.allclose(one["vertex"]["h_p"], after["vertex"]["h_p"], rtol=1e-9)
