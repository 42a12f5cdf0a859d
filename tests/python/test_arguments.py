# test_arguments.py: the Python module's numbers are as strict as the CLI's options: the same ranges and the same
# words (lucent.Error "<argument>: <reason>" where the CLI prints "lucent: --<option>: <reason>").
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest

import lucent
from conftest import run_cli

HELP = " (lucent --help lists the options)"


def cli_reason(*args):
    """The CLI's message for ARGS without "lucent: --<option>: " and the help hint."""
    result = run_cli(*args, check=False)
    assert result.returncode == 1, result.stderr
    line = result.stderr.strip()
    assert line.startswith("lucent: --") and line.endswith(HELP), line
    return line[len("lucent: --"):-len(HELP)].split(": ", 1)


def python_reason(call):
    with pytest.raises(lucent.Error) as error:
        call()
    return str(error.value).split(": ", 1)


SCENE = lucent.load_scene(overrides=["render.width=4", "render.height=3"])  # refused before rendering; small if not
CASES = [
    (lambda: lucent.bssrdf("Skin1", xo=(2000000, 0, 0)), ["bssrdf", "--material", "Skin1", "--xo", "2000000,0,0"]),
    (lambda: lucent.bssrdf("Skin1", xo=(math.nan, 0, 0)), ["bssrdf", "--material", "Skin1", "--xo", "nan,0,0"]),
    (lambda: lucent.bssrdf("Skin1", xi=np.array([0.0, -math.inf, 0.0])),
     ["bssrdf", "--material", "Skin1", "--xi", "0,-inf,0"]),
    (lambda: lucent.bssrdf("Skin1", ni=(0, 0, 2000000)), ["bssrdf", "--material", "Skin1", "--ni", "0,0,2000000"]),
    (lambda: lucent.bssrdf("Skin1", wi=(0, math.nan, 1)), ["bssrdf", "--material", "Skin1", "--wi", "0,nan,1"]),
    (lambda: lucent.bssrdf("Skin1", no=(0, 0, -2000000)), ["bssrdf", "--material", "Skin1", "--no", "0,0,-2000000"]),
    (lambda: lucent.bssrdf("Skin1", eta=5), ["bssrdf", "--material", "Skin1", "--eta", "5"]),
    (lambda: lucent.bssrdf({"sigma_a": 2000000, "sigma_s": 1}), ["bssrdf", "--sigma-a", "2000000", "--sigma-s", "1"]),
    (lambda: lucent.bssrdf({"sigma_a": 1, "sigma_s_prime": math.nan}),
     ["bssrdf", "--sigma-a", "1", "--sigma-s-prime", "nan"]),
    (lambda: lucent.bssrdf({"sigma_a": 1, "sigma_s": 1, "g": 2}),
     ["bssrdf", "--sigma-a", "1", "--sigma-s", "1", "--g", "2"]),
    (lambda: lucent.bssrdf_total("Skin1", incidence_deg=90),
     ["bssrdf", "--material", "Skin1", "--total", "--incidence-deg", "90"]),
    (lambda: lucent.reference(SCENE, threads=100000), ["reference", "s.json", "--threads", "100000"]),
    (lambda: lucent.reference(SCENE, spp=0), ["reference", "s.json", "--spp", "0"]),
    (lambda: lucent.reference(SCENE, seed=-1), ["reference", "s.json", "--seed", "-1"]),
    (lambda: lucent.reference(SCENE, max_scatter=-1), ["reference", "s.json", "--max-scatter", "-1"]),
    (lambda: lucent.compare(np.zeros((2, 2, 3)), np.zeros((2, 2, 3)), exposure=math.nan),
     ["compare", "a.exr", "b.exr", "--exposure", "nan"]),
    (lambda: lucent.write_png(str(Path(tempfile.gettempdir()) / "unwritten.png"), np.zeros((2, 2, 3)), exposure=31),
     ["tonemap", "a.exr", "-o", "b.png", "--exposure", "31"]),
]


@pytest.mark.parametrize("call, cli", CASES, ids=[" ".join(cli) for _, cli in CASES])
def test_same_range_and_message_as_the_cli(call, cli):
    option, reason = cli_reason(*cli)
    argument, python_message = python_reason(call)
    assert argument == option.replace("-", "_")
    assert python_message == reason


def test_values_beyond_a_float():
    # 1e300 would be an infinite float32 and S_d NaN: refused as the CLI refuses --xo 1e300.
    assert python_reason(lambda: lucent.bssrdf("Skin1", xo=(1e300, 0, 0))) == [
        "xo", "1e+300 is out of range; allowed range [-1000000, 1000000] mm"]
    assert python_reason(lambda: lucent.reference(SCENE, seed=2**70)) == [
        "seed", f"{2**70} is out of range; allowed range [0, 1.8e+19]"]


def test_reference_time_is_finite_and_within_the_animation_range():
    # lucent reference renders t = 0; lucent render --animate reaches at most 1e6 frames at 1e-3 frames/s.
    assert python_reason(lambda: lucent.reference(SCENE, time=math.nan)) == [
        "time", "nan is not a finite number; allowed range [0, 1000000000] s"]
    assert python_reason(lambda: lucent.reference(SCENE, time=-1.0)) == [
        "time", "-1 is out of range; allowed range [0, 1000000000] s"]


def test_integers_are_ints():
    assert python_reason(lambda: lucent.reference(SCENE, spp=2.0)) == ["spp", "expected an int, got 2.0"]
    assert python_reason(lambda: lucent.reference(SCENE, threads="4")) == [
        "threads", "expected a whole number, got '4'"]
    assert python_reason(lambda: lucent.bssrdf("Skin1", eta=True)) == ["eta", "expected a number, got True"]


def test_numpy_numbers_in_range_are_taken():
    mean, _ = lucent.reference(SCENE, spp=np.int64(1), seed=np.uint64(5), threads=np.int32(1), time=np.float32(0.0),
                               width=4, height=3)
    assert mean.shape == (3, 4, 3) and np.isfinite(mean).all()
    xo = np.array([0.7, 0.2, 0.0])
    assert lucent.bssrdf("Skin1", xo=xo)["S_d"] == lucent.bssrdf("Skin1", xo=(0.7, 0.2, 0.0))["S_d"]


@pytest.mark.parametrize("keyword, value, text", [("width", 2**40, "1099511627776"), ("frames", 2.5, "2.5"),
                                                  ("seed", -1, "-1")])
def test_render_sizes_are_checked_as_render_values(keyword, value, text):
    # Applied as the overrides render.<keyword>=<value>: the reason the CLI gives for --set, named as Python
    # names the value (a ValueError, not an OverflowError for a large int).
    cli = run_cli("render", "--set", f"render.{keyword}={text}", "-o", "unwritten.png", check=False)
    assert cli.returncode == 1
    with pytest.raises(ValueError) as error:
        lucent.render(SCENE, **{keyword: value})
    reason = cli.stderr.strip().split(f"/render/{keyword}: ", 1)[1]
    assert str(error.value) == f"render.{keyword}: {reason}"
    assert "--set" not in str(error.value)
