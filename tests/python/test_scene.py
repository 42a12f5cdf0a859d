# test_scene.py: lucent.load_scene and Scene.set apply overrides as `lucent render --set` does, with errors in
# Python's terms; the scene reads back typed values, objects and lights by index or name.
import json

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
    assert scene.objects.names() == ["torus", "sphere", "floor"]


def cli_error(*args):
    result = run_cli(*args, check=False)
    assert result.returncode == 1
    return result.stderr


def test_bad_override_is_the_cli_reason_and_keeps_the_scene(out_dir):
    scene = lucent.load_scene()
    with pytest.raises(ValueError) as error:
        scene.set("render.width", -5)
    cli = cli_error("render", "--set", "render.width=-5", "-o", out_dir / "x.png")
    assert cli.startswith("lucent: --set 'render.width=-5': /render/width: ")
    assert str(error.value) == "render.width: " + cli.strip().split("/render/width: ", 1)[1]
    assert scene.width == 640 and scene.overrides == []


def test_missing_file_is_the_cli_message(out_dir):
    missing = str(out_dir / "missing.json")
    with pytest.raises(lucent.Error) as error:
        lucent.load_scene(missing)
    assert isinstance(error.value, RuntimeError)
    assert cli_error("render", missing, "-o", out_dir / "x.png") == f"lucent: {error.value}\n"


def test_scene_path_with_a_nul_byte_is_refused():
    """load_scene('s.json\\0junk') must not load s.json: the name given is not a file's."""
    with pytest.raises(lucent.Error, match=r"NUL byte"):
        lucent.load_scene(str(SCENES / "default.json") + "\0junk")


def test_scene_file_loads():
    scene = lucent.load_scene(str(SCENES / "default.json"), overrides=["render.height=100"])
    assert scene.height == 100 and scene.path.endswith("default.json")


def test_numpy_values_are_written_as_json():
    scene = lucent.load_scene().set("lights.0.radiance", np.array([1.0, 2.0, 3.0], dtype=np.float32))
    scene.set("method", {"name": "per-pixel", "N": np.int64(4)})
    assert scene.overrides == ["lights.0.radiance=[1.0, 2.0, 3.0]", 'method={"name": "per-pixel", "N": 4}']
    assert scene.method == "per-pixel" and scene.method_params["N"] == 4


def test_errors_in_python_terms():
    scene = lucent.load_scene()
    with pytest.raises(lucent.Error, match=r"^unknown method parameter 'NN'; known: K, ") as error:
        scene.set("method.NN", 3)
    with pytest.raises(TypeError, match=r"^method\.K: expected a number, got \"x\"$"):
        scene.set("method.K", "x")
    with pytest.raises(ValueError, match=r"^method\.K: 0 is out of range; allowed range \[1, 64\]"):
        scene.set("method.K", 0)
    with pytest.raises(ValueError, match=r"^render\.tonemap: 'sepia' is not one of"):
        scene.set("render.tonemap", "sepia")
    with pytest.raises(lucent.Error, match=r"^objects\.bunny\.material: 'bunny' is neither an index nor the name"):
        scene.set("objects.bunny.material", "Potato")
    assert "--set" not in str(error.value)
    assert scene.overrides == [] and scene.method_params["K"] == 16


def test_typed_values_as_declared():
    params = lucent.load_scene().method_params
    declared = {p["name"]: p["type"] for p in lucent.methods()[0]["params"]}
    python_type = {"int": int, "float": float, "bool": bool, "enum": str, "string": str}
    for name, value in params.items():
        if declared[name] in python_type:
            assert type(value) is python_type[declared[name]], (name, declared[name], value)
    assert repr(params["K"]) == "16"


def test_objects_and_lights_read_back_as_the_file_writes_them():
    path = SCENES / "default.json"
    doc = json.loads(path.read_text())
    scene = lucent.load_scene(str(path))
    assert scene.objects.names() == [o["name"] for o in doc["objects"]]
    for i, o in enumerate(doc["objects"]):
        view = scene.objects[o["name"]]
        assert view.index == i and scene.objects[i].name == o["name"]
        if "material" in o:
            assert view.material["name"] == o["material"] and view.albedo is None
            preset = next(p for p in lucent.materials() if p["name"] == o["material"])
            assert view.material["sigma_a"] == pytest.approx(preset["sigma_a"], rel=1e-6)
            assert view.material["eta"] == pytest.approx(preset["eta"], rel=1e-6)
        else:
            assert view.material is None and view.albedo == tuple(o["albedo"])
    assert scene.camera["eye"] == tuple(doc["camera"]["eye"]) and scene.camera["fov_y_deg"] == doc["camera"]["fov_y_deg"]
    assert (scene.exposure, scene.tonemap) == (0.0, "aces")  # the defaults of render.exposure, render.tonemap
    scene.set("render.tonemap", "reinhard").set("render.exposure", 0.7)
    assert (scene.exposure, scene.tonemap) == (0.7, "reinhard")
    assert len(scene.lights) == len(doc["lights"])
    assert scene.lights[0]["radiance"] == tuple(doc["lights"][0]["radiance"])
    with pytest.raises(KeyError, match="no objects named 'bunny'"):
        scene.objects["bunny"]
    with pytest.raises(IndexError):
        scene.objects[len(doc["objects"])]


def test_set_by_name_equals_set_by_index():
    by_name = lucent.load_scene().set("objects.sphere.material", "Ketchup").set("objects.sphere.material.eta", 1.45)
    by_index = lucent.load_scene().set("objects.1.material", "Ketchup").set("objects.1.material.eta", 1.45)
    assert by_name.objects["sphere"].material == by_index.objects[1].material
    assert by_name.objects["sphere"].material["name"] == "Ketchup"
    assert by_name.objects["sphere"].material["eta"] == 1.45
    assert by_name.objects["torus"].material == lucent.load_scene().objects["torus"].material
