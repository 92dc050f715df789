"""The interruptible call (python/call_support.cpp): the GIL is released during solves, Ctrl-C raises
KeyboardInterrupt promptly and keeps nothing, progress goes to a Python callback on the calling thread, and
exceptions are Python exceptions."""
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
import _thread

import numpy as np
import pytest

import skinspec

LONG = dict(wavelengths=np.arange(400, 701, 1.0), rays=200_000)  # minutes of work: only ever interrupted


def test_ctrl_c_raises_keyboard_interrupt_promptly():
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        skinspec.spectrum("biospec-moderately", **LONG)
    elapsed = time.monotonic() - start
    assert elapsed < 2.0, f"KeyboardInterrupt {elapsed - 0.5:.2f} s after Ctrl-C"
    # The module is usable afterwards and gives the same numbers as always.
    a = skinspec.spectrum("biospec-lightly", [550], rays=5000)
    b = skinspec.spectrum("biospec-lightly", [550], rays=5000)
    assert a.R[0] == b.R[0]


def test_ctrl_c_stops_a_walk_profile_promptly():
    # skinspec.profiles ran without a stop: Ctrl-C waited for all 5e7 photons per wavelength (over 100 s).
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        skinspec.profiles("biospec-lightly", np.linspace(0, 5, 50), [450, 550, 650], mode="rte", rays=50_000_000)
    elapsed = time.monotonic() - start
    assert elapsed < 2.0, f"KeyboardInterrupt {elapsed - 0.5:.2f} s after Ctrl-C"


def test_sigint_stops_a_script():
    script = textwrap.dedent("""
        import numpy as np, skinspec
        print("solving", flush=True)
        skinspec.spectrum("biospec-moderately", np.arange(400, 701, 1.0), rays=200000)
        print("finished", flush=True)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "solving"
    time.sleep(0.5)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=10)
    assert time.monotonic() - sent < 3.0
    assert "KeyboardInterrupt" in err and "finished" not in out
    assert child.returncode != 0


def test_progress_reaches_a_python_callback_on_the_calling_thread():
    seen = []
    caller = threading.get_ident()

    def progress(p):
        seen.append((threading.get_ident(), p["done"], p["total"], p["rays_done"]))

    skinspec.spectrum("biospec-lightly", np.arange(400, 701, 20), rays=40_000, progress=progress)
    assert seen and all(thread == caller for thread, *_ in seen)
    dones = [d for _, d, _, _ in seen]
    assert dones == sorted(dones) and seen[-1][1] == seen[-1][2] == 16


def test_an_exception_in_the_callback_stops_the_solve():
    def progress(p):
        raise RuntimeError("stop here")

    start = time.monotonic()
    with pytest.raises(RuntimeError, match="stop here"):
        skinspec.spectrum("biospec-moderately", progress=progress, **LONG)
    assert time.monotonic() - start < 5.0


def test_the_gil_is_released_while_solving():
    ticks = 0
    running = True

    def count():
        nonlocal ticks
        while running:
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.monotonic()
    skinspec.spectrum("biospec-lightly", np.arange(400, 701, 10), rays=60_000, threads=1)
    elapsed = time.monotonic() - start
    running = False
    counter.join()
    assert elapsed > 0.2 and ticks > 0.3 * elapsed / 0.001 * 0.5


def test_solver_errors_are_python_exceptions_with_the_cli_message():
    with pytest.raises(skinspec.InputError) as e:
        skinspec.spectrum("biospec-moderately", mode="multipole", quantities="A")
    done = subprocess.run([os.environ["SKINSPEC_PROGRAM"], "spectrum", "--preset", "biospec-moderately", "--mode", "multipole",
                           "--quantities", "A"], capture_output=True, text=True)
    assert done.returncode == 2 and done.stderr.strip() == "skinspec: error: " + str(e.value)
    assert "does not compute A" in str(e.value) and isinstance(e.value, ValueError)
