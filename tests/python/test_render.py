# test_render.py: lucent.render() gives the radiance `lucent render --exr` writes for the same scene, size, frames
# and method settings (one headless context for all renders of the process).
import json
import threading

import numpy as np
import pytest

import lucent
from conftest import run_cli

SIZE = {"width": 64, "height": 40, "frames": 2}
# Small maps: a few seconds on llvmpipe.
RADIOSITY_MAPS = {"K": 8, "N": 16, "map_size": 64, "light_map_size": 128, "vpls": 0}
PER_PIXEL = {"N": 16, "light_map_size": 128}


def cli_render(out_dir, *sets):
    exr = out_dir / "cli.exr"
    args = ["render", "-q", "--frames", SIZE["frames"], "-o", out_dir / "cli.png", "--exr", exr,
            "--set", f"render.width={SIZE['width']}", "--set", f"render.height={SIZE['height']}"]
    for s in sets:
        args += ["--set", s]
    run_cli(*args)
    return lucent.read_exr(str(exr))


def assert_same_image(py, cli):
    assert py.dtype == np.float32 and py.shape == (SIZE["height"], SIZE["width"], 3)
    assert py.max() > 0.01  # lit, not black
    # The same code on the same driver: equal up to float rounding in the accumulation.
    np.testing.assert_allclose(py, cli, rtol=1e-5, atol=1e-6 * float(cli.max()))


def test_default_method_with_parameter_overrides(out_dir):
    py = lucent.render(lucent.load_scene(), params=RADIOSITY_MAPS, **SIZE)
    cli = cli_render(out_dir, *(f"method.{k}={json.dumps(v)}" for k, v in RADIOSITY_MAPS.items()))
    assert_same_image(py, cli)


def test_another_method_and_timings(out_dir):
    py, info = lucent.render(lucent.load_scene(), method="per-pixel", params=PER_PIXEL, timings=True, **SIZE)
    cli = cli_render(out_dir, "method=" + json.dumps({"name": "per-pixel", **PER_PIXEL}))
    assert_same_image(py, cli)
    assert len(info["frames"]) == SIZE["frames"] and info["device"]
    assert all(f["total_ms"] > 0.0 for f in info["frames"])


def test_unknown_method_is_the_cli_reason(out_dir):
    with pytest.raises(lucent.Error) as error:
        lucent.render(lucent.load_scene(), method="no-such-method")
    cli = run_cli("render", "--set", 'method={"name": "no-such-method"}', "-o", out_dir / "x.png", check=False)
    assert cli.returncode == 1
    assert str(error.value) == "method.name: " + cli.stderr.strip().split("/method/name: ", 1)[1]


def test_renders_from_other_threads():
    # A GL context is current on one thread at a time: each render takes the one headless context on its own
    # thread, one render at a time, and lets go of it afterwards, so that any thread may render next.
    scene = lucent.load_scene()
    args = {"method": "per-pixel", "params": PER_PIXEL, "width": 16, "height": 12, "frames": 1}
    first = lucent.render(scene, **args)
    results, errors = [None] * 3, []

    def render(i):
        try:
            results[i] = lucent.render(scene, **args)
        except lucent.Error as error:
            errors.append(str(error))

    threads = [threading.Thread(target=render, args=(i,)) for i in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    assert first.max() > 0.01
    for image in results + [lucent.render(scene, **args)]:  # the last one back on the first thread
        np.testing.assert_array_equal(image, first)  # the same seed and code: the same image


def test_denoise_as_render_denoise(out_dir):
    # denoise=True is the CLI's --denoise; a dict sets the stage's parameters; the stage's passes are timed.
    py, info = lucent.render(lucent.load_scene(), method="per-pixel", params=PER_PIXEL,
                             denoise={"iterations": 2}, timings=True, **SIZE)
    cli = cli_render(out_dir, "method=" + json.dumps({"name": "per-pixel", **PER_PIXEL}), "denoise.enabled=true",
                     "denoise.iterations=2")
    assert_same_image(py, cli)
    assert "denoise_filter" in info["frames"][-1]["passes"]
    raw = lucent.render(lucent.load_scene(), method="per-pixel", params=PER_PIXEL, denoise=False, **SIZE)
    assert np.abs(raw - py).max() > 0.0  # the stage changed the image
    with pytest.raises(ValueError) as error:  # out of its declared range, as `Scene.set` says it
        lucent.render(lucent.load_scene(), denoise={"iterations": 99})
    assert str(error.value).startswith("denoise.iterations: 99 is out of range")
