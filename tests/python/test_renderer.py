# test_renderer.py: lucent.Renderer, built once and rendered many times, gives what lucent.render gives for the
# same scene, camera and edits; bad cameras and edits raise and leave it working; Ctrl-C stops its build.
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

SIZE = {"width": 64, "height": 40}
RADIOSITY_MAPS = {"K": 8, "N": 16, "map_size": 64, "light_map_size": 128, "vpls": 0}
PER_PIXEL = {"N": 16, "light_map_size": 128}


def same_image(live, fresh):
    assert live.dtype == np.float32 and live.shape == fresh.shape
    assert fresh.max() > 0.01  # lit, not black
    # The same code on the same driver: equal up to float rounding in the accumulation.
    np.testing.assert_allclose(live, fresh, rtol=1e-5, atol=1e-6 * float(fresh.max()))


def rmse(a, b):
    return float(np.sqrt(((a - b) ** 2).mean()))


def same_estimate(live, fresh, other_seed, before):
    """After a camera move or an edit the renderer's random streams go on from its frame count, so its image is
    another estimate of the fresh render's: per pixel as close to the fresh render as a render with another seed
    is, while the change itself (before -> fresh) is far larger than that noise."""
    noise = rmse(fresh, other_seed)
    assert rmse(live, fresh) < 1.25 * noise, (rmse(live, fresh), noise)
    assert rmse(before, fresh) > 3.0 * noise, (rmse(before, fresh), noise)


def orbit(camera, degrees):
    """The camera turned about the vertical through its target."""
    a = np.radians(degrees)
    eye, target = np.array(camera["eye"]), np.array(camera["target"])
    d = eye - target
    turned = target + np.array([np.cos(a) * d[0] + np.sin(a) * d[2], d[1], -np.sin(a) * d[0] + np.cos(a) * d[2]])
    return dict(camera, eye=turned.tolist())


FRAMES = 8


def test_first_render_equals_lucent_render_and_edits_give_its_estimates():
    scene = lucent.load_scene()
    with lucent.Renderer(scene, params=RADIOSITY_MAPS, **SIZE) as renderer:
        first = renderer.render(frames=2)
        same_image(first, lucent.render(scene, params=RADIOSITY_MAPS, frames=2, **SIZE))
        assert renderer.accumulated_frames == 2

        renderer.set("objects.sphere.material", "Skin1")  # a material edit: the method keeps its shaders
        edited = renderer.render(frames=FRAMES)
        assert renderer.accumulated_frames == FRAMES  # the edit restarted the accumulation
        assert renderer.scene.objects["sphere"].material["name"] == "Skin1"
        assert scene.objects["sphere"].material["name"] == "Marble"  # the renderer edits its own copy
        skin = lucent.load_scene().set("objects.sphere.material", "Skin1")
        fresh = lucent.render(skin, params=RADIOSITY_MAPS, frames=FRAMES, **SIZE)
        same_estimate(edited, fresh, lucent.render(skin, params=RADIOSITY_MAPS, frames=FRAMES, seed=7, **SIZE), first)

        renderer.set("method.specular", False)  # declared live: taken per frame, no rebuild
        live = renderer.render(frames=FRAMES)
        matte = dict(RADIOSITY_MAPS, specular=False)
        same_estimate(live, lucent.render(skin, params=matte, frames=FRAMES, **SIZE),
                      lucent.render(skin, params=matte, frames=FRAMES, seed=7, **SIZE), fresh)


def test_a_camera_gives_a_fresh_renders_estimate_and_a_size_edit_a_new_size():
    scene = lucent.load_scene()
    turned = orbit(scene.camera, 20.0)
    moved_scene = lucent.load_scene().set("camera.eye", turned["eye"])
    with lucent.Renderer(scene, method="per-pixel", params=PER_PIXEL, **SIZE) as renderer:
        before = renderer.render(frames=2)
        moved = renderer.render(camera=turned, frames=FRAMES)
        assert renderer.camera["eye"] == pytest.approx(turned["eye"], abs=1e-5)
        same_estimate(moved, lucent.render(moved_scene, method="per-pixel", params=PER_PIXEL, frames=FRAMES, **SIZE),
                      lucent.render(moved_scene, method="per-pixel", params=PER_PIXEL, frames=FRAMES, seed=7, **SIZE),
                      before)
        renderer.set("render.width", 48)  # a new size: a new target
        assert renderer.render().shape == (SIZE["height"], 48, 3)


def test_bad_cameras_and_edits_raise_and_keep_the_renderer():
    scene = lucent.load_scene()
    renderer = lucent.Renderer(scene, method="per-pixel", params=PER_PIXEL, **SIZE)
    renderer.render(frames=2)
    camera = scene.camera
    for bad, error, words in [
        (dict(camera, eye=camera["target"]), ValueError, "eye and target are the same point"),
        (dict(camera, up=[0, 0, 0]), ValueError, "camera.up"),
        (dict(camera, fov_y_deg=180), ValueError, "camera.fov_y_deg: 180"),
        (dict(camera, eye=[0, float("nan"), 0]), ValueError, "camera.eye[1]: nan is not finite"),
        (dict(camera, eye=[0, 1]), TypeError, "camera.eye: expected three numbers"),
        (dict(camera, zoom=2), ValueError, "unknown key 'zoom'"),
    ]:
        with pytest.raises(error, match=words.replace("[", r"\[").replace("]", r"\]")):
            renderer.render(camera=bad)
    with pytest.raises(ValueError, match=r"method.N: 0 is out of range"):
        renderer.set("method.N", 0)
    with pytest.raises(ValueError, match="frames: 0 is out of range"):
        renderer.render(frames=0)
    # Nothing was applied: the next frames go on accumulating the same view and scene.
    assert renderer.camera["eye"] == pytest.approx(camera["eye"])
    renderer.render(frames=2)
    assert renderer.accumulated_frames == 4


def test_closed_and_released_renderers_raise():
    renderer = lucent.Renderer(lucent.load_scene(), method="per-pixel", params=PER_PIXEL, **SIZE)
    renderer.close()
    assert renderer.closed
    with pytest.raises(lucent.Error, match="closed"):
        renderer.render()
    renderer = lucent.Renderer(lucent.load_scene(), method="per-pixel", params=PER_PIXEL, **SIZE)
    lucent.release()  # the renderer's objects go with the context, first
    assert renderer.closed
    with pytest.raises(lucent.Error, match="closed"):
        renderer.set("method.N", 8)
    assert lucent.render(lucent.load_scene(), method="per-pixel", params=PER_PIXEL, frames=1, **SIZE).max() > 0


def test_sigint_stops_the_build_within_a_second(tmp_path):
    # local-global's precomputation with an empty cache takes about 10 s on two cores: SIGINT after 1 s.
    script = textwrap.dedent(f"""
        import os, signal, threading, time, lucent
        steps = []
        scene = lucent.load_scene()
        sent = []
        def interrupt():
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)
        threading.Timer(1.0, interrupt).start()
        try:
            lucent.Renderer(scene, method="local-global", width=32, height=20,
                            progress=lambda step, fraction: steps.append(step))
            print("built", flush=True)
        except KeyboardInterrupt:
            print(f"interrupted {{time.monotonic() - sent[0]:.3f}} {{sorted(set(steps))}}", flush=True)
        os._exit(0)
    """)
    env = dict(os.environ, LUCENT_CACHE_DIR=str(tmp_path))
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, env=env)
    assert result.stdout.startswith("interrupted"), (result.stdout, result.stderr)
    took = float(result.stdout.split()[1])
    assert took < 1.0, f"KeyboardInterrupt came {took:.2f} s after SIGINT"
    assert "renderer" in result.stdout and "local-global" in result.stdout  # progress named the steps


def test_a_rebuild_that_fails_puts_the_last_good_scene_back():
    # A rebuild that reports progress (layered-parallax's texture atlas) after the build's own call has returned,
    # then one that fails in the middle (an atlas too small for the charts): the renderer keeps its last good scene.
    small = {"atlas_size": 64, "texture_size": 16, "irradiance_map_size": 16, "light_map_size": 8}
    renderer = lucent.Renderer(lucent.load_scene(), method="layered-parallax", params=small, width=32, height=20)
    before = renderer.render(frames=2)
    renderer.set("method.atlas_size", 128)  # rebuilds, reporting through the renderer's progress
    assert renderer.render().max() > 0.01
    with pytest.raises(lucent.Error, match="do not fit into a 32 x 32 atlas"):
        renderer.set("method.atlas_size", 32)
    assert not renderer.closed and renderer.scene.method_params["atlas_size"] == 128
    assert renderer.render().max() > 0.01
    # radiosity-maps: a map direction of zero length fails when the method is made, after the old one is gone.
    renderer = lucent.Renderer(lucent.load_scene(), params=RADIOSITY_MAPS, **SIZE)
    before = renderer.render(frames=2)
    with pytest.raises(lucent.Error, match="must be a non-zero vector"):
        renderer.set("method.map_directions", [[0, 0, 0]])
    assert renderer.accumulated_frames == 0  # rebuilt: the last good scene from its first frame
    # The same scene again (its random streams go on from the frame count: within the noise of two frames).
    assert rmse(renderer.render(frames=2), before) < 0.01


def test_a_second_threads_call_is_refused_and_bad_arguments_raise():
    renderer = lucent.Renderer(lucent.load_scene(), method="per-pixel", params=PER_PIXEL, **SIZE)
    refused = []

    def second():
        time.sleep(0.3)
        try:
            renderer.render()
        except lucent.Error as e:
            refused.append(str(e))

    thread = threading.Thread(target=second)
    thread.start()
    renderer.render(frames=60)
    thread.join()
    assert refused and "in use by another thread's call" in refused[0]
    camera = lucent.load_scene().camera
    with pytest.raises(ValueError, match=r"frames: 1099511627776 is out of range"):
        renderer.render(frames=2 ** 40)
    with pytest.raises(TypeError, match="frames: expected an integer"):
        renderer.render(frames=2.0)
    with pytest.raises(ValueError, match=r"camera.fov_y_deg: 1e-50 is out of range; allowed range \[1, 179\]"):
        renderer.render(camera=dict(camera, fov_y_deg=1e-50))
    with pytest.raises(TypeError, match="camera.eye: expected three numbers"):
        renderer.render(camera=dict(camera, eye=b"abc"))
    with pytest.raises(ValueError, match=r"camera.eye\[0\]: 1e\+20 is out of range"):
        renderer.render(camera=dict(camera, eye=[1e20, 0, 0]))
    with pytest.raises(ValueError, match="eye and target are the same point"):
        renderer.render(camera=dict(camera, eye=[camera["target"][0], camera["target"][1], camera["target"][2] + 1e-9]))


def test_animation_time_and_restart():
    scene = lucent.load_scene(str(SCENES / "deforming_organ.json"))
    with lucent.Renderer(scene, method="per-pixel", params=PER_PIXEL, **SIZE) as renderer:
        still = renderer.render(frames=2)
        assert renderer.time == 0.0
        renderer.time = 0.75  # a quarter of the bend's 3 s period: the organ is bent
        bent = renderer.render(frames=2)
        assert renderer.accumulated_frames == 2  # the new shape restarted the accumulation
        assert rmse(bent, still) > 0.01
        renderer.restart()
        renderer.render()
        assert renderer.accumulated_frames == 1
        with pytest.raises(ValueError, match="time: nan is out of range"):
            renderer.time = float("nan")
