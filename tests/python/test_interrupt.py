# test_interrupt.py: long calls answer Ctrl-C (SIGINT) with KeyboardInterrupt within a second, call their progress
# callback on the calling thread, and leave the module usable.
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import lucent
from conftest import SCENES

# 4096 samples per pixel of the default scene: minutes on a few cores, so a return within 2 s is the interrupt.
LONG_REFERENCE = dict(spp=4096, width=96, height=64)
SMALL = dict(spp=2, seed=3, width=12, height=8)


def test_sigint_stops_a_long_reference_in_a_child_process():
    script = textwrap.dedent(f"""
        import sys, lucent
        scene = lucent.load_scene({str(SCENES / "default.json")!r})
        print("rendering", flush=True)
        # No progress callback: no Python code runs during the call, so only the call's own signal check can
        # raise (a Python callback would see the pending signal itself).
        lucent.reference(scene, **{LONG_REFERENCE!r})
        print("finished", flush=True)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=os.environ.copy())
    try:
        assert child.stdout.readline() == "rendering\n"
        time.sleep(1.0)  # inside the render (setup takes a fraction of a second; the samples, minutes)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        child.wait(timeout=30)
        took = time.monotonic() - sent
    finally:
        child.kill()
        stdout, stderr = child.communicate()
    assert took < 2.0, f"the reference went on for {took:.1f} s after SIGINT"
    assert "finished" not in stdout
    # Python ends an uncaught KeyboardInterrupt by dying of SIGINT, after printing the traceback.
    assert child.returncode == -signal.SIGINT, (child.returncode, stderr)
    assert stderr.rstrip().endswith("KeyboardInterrupt"), stderr


def interrupt_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_caught_interrupt_leaves_the_module_usable():
    scene = lucent.load_scene(str(SCENES / "default.json"))
    before = lucent.reference(scene, **SMALL)
    fractions = []
    start = time.monotonic()

    def progress(fraction):
        fractions.append(fraction)
        if time.monotonic() - start > 10.0:  # not interrupted: end the test rather than wait for the render
            raise AssertionError("still rendering 9 s after SIGINT")

    timer = interrupt_after(1.0)
    with pytest.raises(KeyboardInterrupt):
        lucent.reference(scene, progress=progress, **LONG_REFERENCE)
    timer.join()
    assert time.monotonic() - start < 10.0
    assert fractions and all(0.0 <= f < 1.0 for f in fractions) and fractions == sorted(fractions)
    after = lucent.reference(scene, **SMALL)
    np.testing.assert_array_equal(before[0], after[0])
    np.testing.assert_array_equal(before[1], after[1])


def test_progress_reaches_one_and_is_called_on_the_calling_thread():
    calls = []
    lucent.reference(lucent.load_scene(), progress=lambda f: calls.append((f, threading.get_ident())), **SMALL)
    assert calls[-1][0] == 1.0
    assert {thread for _, thread in calls} == {threading.get_ident()}
    assert [f for f, _ in calls] == sorted(f for f, _ in calls)


def test_an_exception_in_progress_stops_the_call():
    class Enough(Exception):
        pass

    def stop(fraction):
        raise Enough(fraction)

    with pytest.raises(Enough):
        lucent.reference(lucent.load_scene(), progress=stop, **LONG_REFERENCE)
    with pytest.raises(TypeError, match="progress"):
        lucent.reference(lucent.load_scene(), progress=3, **SMALL)


def test_sigint_stops_a_render_of_many_frames():
    scene = lucent.load_scene()
    args = dict(method="per-pixel", params={"N": 4, "light_map_size": 64}, width=16, height=12)
    first = lucent.render(scene, frames=1, **args)
    seen = threading.Event()

    def progress(fraction):
        if not seen.is_set():
            seen.set()
            os.kill(os.getpid(), signal.SIGINT)
        elif time.monotonic() - start > 60.0:  # not interrupted: end the test rather than render a million frames
            raise AssertionError("still rendering a minute after SIGINT")

    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        lucent.render(scene, frames=1000000, progress=progress, **args)
    assert seen.is_set() and time.monotonic() - start < 60.0
    np.testing.assert_array_equal(lucent.render(scene, frames=1, **args), first)


def test_sigint_stops_a_model_total_that_cannot_poll():
    # The photon-beam model's total integrates for seconds in code with no stop flag: the call returns at once and
    # the integration finishes on its own thread, unused.
    expected = lucent.bssrdf_total("Marble", model="standard")
    timer = interrupt_after(0.5)
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        lucent.bssrdf_total("Marble", model="photon-beam", incidence_deg=45)
    timer.join()
    assert time.monotonic() - start < 2.0
    assert lucent.bssrdf_total("Marble", model="standard") == expected
