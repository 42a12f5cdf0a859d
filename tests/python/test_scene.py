# test_scene.py: lucent.load_scene and Scene.set apply overrides as `lucent render --set` does, and their errors
# are the CLI's line.
import numpy as np
import pytest

import lucent
from conftest import SCENES, run_cli


def test_default_scene_and_overrides():
    scene = lucent.load_scene()
    assert scene.path is None and scene.method == "radiosity-maps"
    assert (scene.width, scene.height) == (640, 400)
    assert scene.method_params["K"] == 16
    scene.set("method.K", 8).set("render.width", 320).set("objects.1.material", "Potato")
    assert scene.method_params["K"] == 8 and scene.width == 320
    assert scene.overrides == ["method.K=8", "render.width=320", 'objects.1.material="Potato"']
    assert scene.objects == ["torus", "sphere", "floor"]


def cli_error(*args):
    result = run_cli(*args, check=False)
    assert result.returncode == 1
    return result.stderr


def test_bad_override_is_the_cli_message_and_keeps_the_scene(out_dir):
    scene = lucent.load_scene()
    with pytest.raises(lucent.Error) as error:
        scene.set("render.width", -5)
    assert cli_error("render", "--set", "render.width=-5", "-o", out_dir / "x.png") == f"lucent: {error.value}\n"
    assert scene.width == 640 and scene.overrides == []


def test_missing_file_is_the_cli_message(out_dir):
    missing = str(out_dir / "missing.json")
    with pytest.raises(lucent.Error) as error:
        lucent.load_scene(missing)
    assert isinstance(error.value, RuntimeError)
    assert cli_error("render", missing, "-o", out_dir / "x.png") == f"lucent: {error.value}\n"


def test_scene_file_loads():
    scene = lucent.load_scene(str(SCENES / "default.json"), overrides=["render.height=100"])
    assert scene.height == 100 and scene.path.endswith("default.json")


def test_numpy_values_are_written_as_json():
    scene = lucent.load_scene().set("lights.0.radiance", np.array([1.0, 2.0, 3.0], dtype=np.float32))
    scene.set("method", {"name": "per-pixel", "N": np.int64(4)})
    assert scene.overrides == ["lights.0.radiance=[1.0, 2.0, 3.0]", 'method={"name": "per-pixel", "N": 4}']
    assert scene.method == "per-pixel" and scene.method_params["N"] == 4
